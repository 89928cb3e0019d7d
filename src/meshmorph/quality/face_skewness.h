// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Face skewness: how far the face centre lies from where the line between the cell
//! centres crosses the face, relative to the cell-centre distance (OpenFOAM
//! primitiveMeshTools::faceSkewness and boundaryFaceSkewness).
#pragma once

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief Skewness per face (nFaces). A boundary face measures against the owner centre's
//! projection onto the face normal, with twice the normalisation factor. OpenMP over faces.
Eigen::VectorXd face_skewness(const PolyMesh& mesh, const MeshGeometry& geometry);

//! \brief The skewness of face f alone, as face_skewness(mesh, geometry) computes it (which
//! computes most quads eight at a time, to the same bits).
double face_skewness_at(const PolyMesh& mesh, const MeshGeometry& geometry, Index f);

//! \brief checkMesh's (polyMeshTools::faceSkewness): as above, but cyclic faces measure
//! against the cell across them, as internal faces do.
Eigen::VectorXd face_skewness(const PolyMesh& mesh, const MeshGeometry& geometry,
                              const CoupledFaces& coupled);

//! \brief face_skewness(mesh, geometry, coupled) where only its largest value and the faces
//! above `threshold` are wanted (checkMesh's maxSkewness and skewFaces): exact, to the same
//! bits, at every face above the threshold and at the largest; 0 at faces that can be
//! neither. A bound without the vertices' term (the gathers of the face's points, most of
//! the metric's cost) screens the faces first; a variant's check on the motorBike then
//! computes the whole metric for the few faces above 4 only.
Eigen::VectorXd screened_face_skewness(const PolyMesh& mesh, const MeshGeometry& geometry,
                                       const CoupledFaces& coupled, double threshold);

//! \brief Per cell, the largest skewness of its faces (0 for a cell without faces).
//! \param skewness face_skewness(mesh, geometry). \return nCells values.
Eigen::VectorXd cell_skewness(const CompactList& cell_faces, const Eigen::VectorXd& skewness);

} // namespace meshmorph
