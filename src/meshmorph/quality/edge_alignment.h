// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Edge alignment of 2D and 1D meshes (OpenFOAM polyMesh::checkEdgeAlignment): every
//! edge must lie along the valid directions or be perpendicular to them.
#pragma once

#include <utility>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! An undirected mesh edge (smaller point label first).
using Edge = std::pair<Index, Index>;

//! \brief The edges (p0 < p1, sorted, distinct) whose direction has a component both along
//! an empty direction and along another direction, or along two empty directions
//! (components above 1e-6 of the unit edge count; edges shorter than ROOTVSMALL are skipped).
std::vector<Edge> non_aligned_edges(const PolyMesh& mesh, const MeshDirections& directions);

} // namespace meshmorph
