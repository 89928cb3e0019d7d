// SPDX-License-Identifier: GPL-3.0-or-later
// Negative volumes and face-pyramid orientation: checkMesh's own metric and checks, without
// its report (face_pyramid_errors is with the pyramid volumes, in face_pyramids.cpp).
#include "meshmorph/quality/cell_validity.h"

#include "meshmorph/quality/geometry_checks.h"

namespace meshmorph
{

InvalidCells count_invalid_cells(const PolyMesh& mesh, const MeshGeometry& g,
                                 std::vector<char>* pyramid_errors)
{
    std::vector<char> errors = face_pyramid_errors(mesh, g);
    const InvalidCells counts{check_cell_volumes(g.cell_volumes).count("negativeVolumeCells"),
                              check_face_pyramids(errors).count("incorrectlyOrientedFacePyramids")};
    if (pyramid_errors != nullptr)
        *pyramid_errors = std::move(errors);
    return counts;
}

} // namespace meshmorph
