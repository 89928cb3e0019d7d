// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Face twist (snappyHexMesh's minTwist and minTriangleTwist, OpenFOAM
//! polyMeshGeometry::checkFaceTwist / checkTriangleTwist): how far the triangles fanned from
//! a face centre turn away from the cell-centre direction and from each other.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief Whether a face of more than 3 points has a fan triangle (area > VSMALL) whose unit
//! normal has a dot product < min_twist with the unit cell-centre direction (owner ->
//! neighbour, or owner -> face centre on the boundary). OpenMP over faces. \return nFaces flags.
//! \param coupled if given, coupled faces use the cell centre across them (polyMeshGeometry).
std::vector<char> faces_with_twist_below(const PolyMesh& mesh, const MeshGeometry& geometry,
                                         double min_twist, const CoupledFaces* coupled = nullptr);

//! \brief Whether a face of more than 3 points has consecutive fan triangles (area > VSMALL)
//! whose unit normals have a dot product < min_twist, or, when min_twist > 0, a degenerate
//! triangle after the first valid one. OpenMP over faces. \return nFaces flags.
std::vector<char> faces_with_triangle_twist_below(const PolyMesh& mesh,
                                                  const MeshGeometry& geometry, double min_twist);

} // namespace meshmorph
