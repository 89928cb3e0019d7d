// SPDX-License-Identifier: GPL-3.0-or-later
// Negative volumes and face-pyramid orientation: checkMesh's own metric and checks, without
// its report.
#include "meshmorph/quality/cell_validity.h"

#include "meshmorph/quality/face_pyramids.h"
#include "meshmorph/quality/geometry_checks.h"

namespace meshmorph
{

std::vector<char> face_pyramid_errors(const PolyMesh& mesh, const MeshGeometry& g)
{
    const FacePyramidVolumes v = face_pyramid_volumes(mesh, g);
    const Index n_int = mesh.n_internal_faces();
    std::vector<char> n_err(static_cast<std::size_t>(mesh.n_faces()), 0);
    for (Index f = 0; f < mesh.n_faces(); ++f)
        n_err[f] = static_cast<char>((v.owner[f] < -constants::small) +
                                     (f < n_int && v.neighbour[f] < -constants::small));
    return n_err;
}

InvalidCells count_invalid_cells(const PolyMesh& mesh, const MeshGeometry& g)
{
    return {
        check_cell_volumes(g.cell_volumes).count("negativeVolumeCells"),
        check_face_pyramids(face_pyramid_errors(mesh, g)).count("incorrectlyOrientedFacePyramids")};
}

} // namespace meshmorph
