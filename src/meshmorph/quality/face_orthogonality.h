// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Face orthogonality: the cosine of the angle between a face's area vector and the
//! line joining the cell centres on either side (OpenFOAM primitiveMeshTools::faceOrthogonality).
#pragma once

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief cos(theta) = (d . Af) / (|d| |Af| + eps) per face, d = Cc(neighbour) - Cc(owner).
//! \param eps checkMesh adds ROOTVSMALL (1e-150); snappyHexMesh's maxNonOrtho VSMALL.
//! \return nFaces values; boundary faces (which have no neighbour) get 1. OpenMP over faces.
Eigen::VectorXd face_orthogonality(const PolyMesh& mesh, const MeshGeometry& geometry,
                                   double eps = constants::rootvsmall);

//! \brief face_orthogonality's value for the internal face f alone.
double internal_face_orthogonality(const PolyMesh& mesh, const MeshGeometry& geometry, Index f,
                                   double eps = constants::rootvsmall);

//! \brief checkMesh's (polyMeshTools::faceOrthogonality): as above, with cyclic and processor
//! faces measured against the cell across them. \return nFaces values.
Eigen::VectorXd face_orthogonality(const PolyMesh& mesh, const MeshGeometry& geometry,
                                   const CoupledFaces& coupled, double eps = constants::rootvsmall);

//! \brief The value of the overload above for the coupled boundary face f alone.
double coupled_face_orthogonality(const PolyMesh& mesh, const MeshGeometry& geometry,
                                  const CoupledFaces& coupled, Index f,
                                  double eps = constants::rootvsmall);

//! \brief Per cell, the largest non-orthogonality [deg] of its faces: acos of the smallest
//! face_orthogonality, clamped to [-1, 1] (0 for a cell without faces).
//! \param orthogonality face_orthogonality(mesh, geometry). \return nCells values.
Eigen::VectorXd cell_non_orthogonality(const CompactList& cell_faces,
                                       const Eigen::VectorXd& orthogonality);

//! \brief An angle [deg] from a cosine clamped to [-1, 1], in OpenFOAM's operation order.
double non_orthogonality_degrees(double cosine);

} // namespace meshmorph
