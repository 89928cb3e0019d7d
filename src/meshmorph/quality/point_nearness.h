// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Points closer together than a distance (OpenFOAM primitiveMesh::checkPointNearness,
//! which checkMesh -allGeometry runs after the edge lengths).
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! \brief Per point (nPoints): marked when it is one of a pair closer than sqrt(dist_sqr).
//!
//! As OpenFOAM: the points are sorted by |p|^2 and each is compared with the points before
//! it whose |p|^2 exceeds its own minus dist_sqr only. That window is a heuristic (two points
//! a distance d apart can differ by more than d^2 in |p|^2), so a close pair far from the
//! origin can go unreported; checkMesh misses the same pairs, and so do we.
std::vector<char> near_points(const PolyMesh& mesh, double dist_sqr);

} // namespace meshmorph
