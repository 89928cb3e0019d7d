// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The two checks that decide whether a mesh can be solved on at all: negative cell
//! volumes and wrongly oriented face pyramids (checkMesh's checkCellVolumes and
//! checkFacePyramids, OpenFOAM primitiveMeshCheck.C). A morph in steps asks only these:
//! count_invalid_cells runs the two checks of geometry_checks.h, without check_mesh's other
//! checks or its report.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief Per face, how many of its (owner, neighbour) pyramids are wrongly oriented: the
//! pyramid of a face with apex at the cell centre has volume < -1e-15 (OpenFOAM's SMALL).
//! OpenMP over faces. \return nFaces entries in {0, 1, 2}.
std::vector<char> face_pyramid_errors(const PolyMesh& mesh, const MeshGeometry& geometry);

struct InvalidCells
{
    Index negative_volume_cells = 0; //!< volume < 1e-300 (OpenFOAM's VSMALL), as checkMesh
    Index wrong_pyramids = 0;        //!< sum of face_pyramid_errors
    //! True when either count is higher than in `before` (a morph made the mesh worse).
    bool worse_than(const InvalidCells& before) const
    {
        return negative_volume_cells > before.negative_volume_cells ||
               wrong_pyramids > before.wrong_pyramids;
    }
};

//! \brief Both counts for a mesh and its geometry (compute_geometry): check_cell_volumes
//! and check_face_pyramids. \param pyramid_errors if given, receives the
//! face_pyramid_errors counted (a later check_mesh of the same points takes them over:
//! CheckMeshSettings::face_pyramid_errors).
InvalidCells count_invalid_cells(const PolyMesh& mesh, const MeshGeometry& geometry,
                                 std::vector<char>* pyramid_errors = nullptr);

} // namespace meshmorph
