// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Face interpolation weights (OpenFOAM primitiveMeshTools::faceWeights and
//! polyMeshGeometry::checkFaceWeights): how evenly an internal face sits between its cell
//! centres.
#pragma once

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief min(d_own, d_nei) / (d_own + d_nei + VSMALL) per internal face, d the distances
//! (times |Af|) of the cell centres from the face plane: 0.5 for a face halfway.
//! OpenMP over faces. \return nInternalFaces values.
Eigen::VectorXd face_weights(const PolyMesh& mesh, const MeshGeometry& geometry);

//! \brief checkMesh's (polyMeshTools::faceWeights): the same over internal and cyclic faces
//! (against the cell across), 1 on the other boundary faces. \return nFaces values.
Eigen::VectorXd face_weights(const PolyMesh& mesh, const MeshGeometry& geometry,
                             const CoupledFaces& coupled);

//! \brief min(V_own, V_nei) / (max(V_own, V_nei) + VSMALL) per internal face.
//! \param cell_volumes the signed volumes (checkMesh) or their magnitudes (snappyHexMesh).
//! \return nInternalFaces values.
Eigen::VectorXd face_volume_ratio(const PolyMesh& mesh, const Eigen::VectorXd& cell_volumes);

//! \brief checkMesh's (polyMeshTools::volRatio): the same over internal and cyclic faces
//! (against the cell across), 1 on the other boundary faces. \return nFaces values.
Eigen::VectorXd face_volume_ratio(const PolyMesh& mesh, const Eigen::VectorXd& cell_volumes,
                                  const CoupledFaces& coupled);

} // namespace meshmorph
