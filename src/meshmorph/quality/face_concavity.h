// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Concave face corners: corners where consecutive edges turn against the face normal
//! (OpenFOAM primitiveMeshTools::faceConcavity for checkMesh, polyMeshGeometry::
//! checkFaceAngles for snappyHexMesh's maxConcave).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief checkMesh's concavity per face: the largest sin of a concave corner angle, over
//! corners turning by at least 10 degrees (0 for a convex face). OpenMP over faces.
//! \return nFaces values in [0, 1].
Eigen::VectorXd face_concavity(const PolyMesh& mesh, const MeshGeometry& geometry);

//! \brief snappyHexMesh's maxConcave: whether a face has a concave corner turning by at
//! least asin(max_sin). OpenMP over faces. \return nFaces flags.
std::vector<char> faces_concave_beyond(const PolyMesh& mesh, const MeshGeometry& geometry,
                                       double max_sin);

} // namespace meshmorph
