// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Mesh edges: packed edge keys, and the edge counts of checkMesh's "Mesh stats" with
//! -allTopology (OpenFOAM primitiveMesh::nEdges / nInternalEdges and the boundary-point
//! counts of checkTopology).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

struct EdgeCounts
{
    std::int64_t edges = 0;          //!< distinct undirected face edges
    std::int64_t internal_edges = 0; //!< edges used by no boundary face
    std::int64_t internal_edges_one_boundary_point = 0;
    std::int64_t internal_edges_two_boundary_points = 0;
};

//! \brief An undirected edge as one sortable integer (smaller label in the high half).
inline std::uint64_t packed_edge(Index a, Index b)
{
    const std::uint32_t lo = static_cast<std::uint32_t>(std::min(a, b));
    const std::uint32_t hi = static_cast<std::uint32_t>(std::max(a, b));
    return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

//! \brief Count the edges. \param point_faces point_faces(mesh).
//! \param boundary_points boundary_point_mask(mesh). OpenMP over points.
EdgeCounts count_edges(const PolyMesh& mesh, const CompactList& point_faces,
                       const std::vector<char>& boundary_points);

} // namespace meshmorph
