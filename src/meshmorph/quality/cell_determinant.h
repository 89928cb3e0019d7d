// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Cell determinants: how well the face area vectors of a cell span all directions
//! (OpenFOAM primitiveMeshTools::cellDeterminant for checkMesh, and polyMeshGeometry's
//! scaled determinant for snappyHexMesh's minDeterminant).
#pragma once

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief checkMesh's cell determinant: |det(sum over internal faces of a a^T)| / 8 with
//! a = Af / mean |Af| (1 in 1D; empty directions count as 1 in 2D; 0 for a cell without
//! internal faces). Always computed by check_mesh (a VTK field). OpenMP over cells.
//! \param face_area_magnitudes face_area_magnitudes(geometry). \return nCells values.
Eigen::VectorXd cell_determinant(const PolyMesh& mesh, const CompactList& cell_faces,
                                 const MeshGeometry& geometry, const MeshDirections& directions,
                                 const Eigen::VectorXd& face_area_magnitudes);

//! \brief The same over internal and cyclic faces (syncTools::getInternalOrCoupledFaces), as
//! checkMesh (polyMesh::checkCellDeterminant) computes it.
Eigen::VectorXd cell_determinant(const PolyMesh& mesh, const CompactList& cell_faces,
                                 const MeshGeometry& geometry, const MeshDirections& directions,
                                 const Eigen::VectorXd& face_area_magnitudes,
                                 const CoupledFaces& coupled);

//! \brief snappyHexMesh's determinant: det(sum over all faces of Af Af^T / |Af|, divided by
//! the sum of |Af|) / (1/27), so 1 for a cube. OpenMP over cells. \return nCells values.
Eigen::VectorXd cell_area_determinant(const CompactList& cell_faces, const MeshGeometry& geometry);

} // namespace meshmorph
