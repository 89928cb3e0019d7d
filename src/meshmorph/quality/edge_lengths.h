// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Edge lengths of the face loops (OpenFOAM primitiveMesh::checkEdgeLength).
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! The extreme edge lengths and the points on short edges.
struct EdgeLengths
{
    double min_length = 0, max_length = 0; //!< over every face edge
    //! Per point (nPoints): marked as on a short edge. For each short edge in face order
    //! the first of its two points not yet marked is marked (OpenFOAM's short-circuit
    //! `set.insert(a) || set.insert(b)`), so at most one point per edge.
    std::vector<char> short_edge_points;
    Index n_short = 0; //!< points marked
};

//! \brief Walk every face edge once per face using it. \param min_length_sqr an edge is
//! short when its squared length is below this (checkMesh: |1e-6 * bounding box span|^2).
EdgeLengths edge_lengths(const PolyMesh& mesh, double min_length_sqr);

} // namespace meshmorph
