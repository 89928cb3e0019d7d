// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Face-decomposition tets: the tets (face edge, face centre, cell centre) and
//! (cell centre, base point, face edge) that OpenFOAM's tet decomposition builds on a face
//! (polyMeshTetDecomposition), checked for positive volume and quality.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief checkMesh's face tet errors (polyMesh::checkFaceTets): per face, one error for a
//! non-negative owner tet (face edge, face centre, owner centre), one for a non-positive
//! neighbour tet, one when no face point is a valid decomposition base (every tet from it
//! has quality > SMALL^2). OpenMP over faces. \return nFaces entries in {0, 1, 2, 3}.
std::vector<char> face_tet_errors(const PolyMesh& mesh, const MeshGeometry& geometry);

//! \brief snappyHexMesh's minTetQuality (polyMeshGeometry::checkFaceTets): whether a face
//! has a tet of quality < min_quality, or no decomposition base point with all tets above
//! it. OpenMP over faces. \return nFaces flags.
std::vector<char> faces_with_tet_quality_below(const PolyMesh& mesh, const MeshGeometry& geometry,
                                               double min_quality,
                                               const CoupledFaces* coupled = nullptr);

} // namespace meshmorph
