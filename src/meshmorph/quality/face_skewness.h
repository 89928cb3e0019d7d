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

//! \brief Per cell, the largest skewness of its faces (0 for a cell without faces).
//! \param skewness face_skewness(mesh, geometry). \return nCells values.
Eigen::VectorXd cell_skewness(const CompactList& cell_faces, const Eigen::VectorXd& skewness);

} // namespace meshmorph
