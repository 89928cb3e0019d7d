// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: the records of IdwTree's source tree and its coincidence distance, shared by the
//! tree (idw_tree.h) and the evaluation kernels (idw_kernels.h).
#pragma once

#include "meshmorph/core/types.h"

namespace meshmorph::detail
{

//! Squared distance below which a query is taken to sit on a source (normalised units:
//! 1e-13 of the sources' extent, far below any mesh spacing, far above round-off).
inline constexpr double idw_coincident2 = 1e-26;

//! A node of the source tree: its ball, its range of sources (tree order) or children, and
//! the moments of its sources about their centroid.
struct IdwNode
{
    double cx = 0, cy = 0, cz = 0; //!< centroid
    double radius = 0.0;           //!< about the centroid
    Index begin = 0, end = 0;
    Index child = -1; //!< first child (the second follows it); -1: leaf
    // Moments about the centroid, delta = s - centroid.
    double count = 0.0;
    double sv[3] = {0, 0, 0};   //!< sum v
    double first[3][3] = {};    //!< [a][k] = sum delta_a v_k
    double second[6] = {};      //!< sum delta delta^T: xx yy zz xy xz yz
    double second_v[3][6] = {}; //!< [k] = sum delta delta^T v_k (same layout)
    double trace[4] = {};       //!< of second, second_v[0..2]
    //! Written without its sources (write_essential): it must only ever be far.
    bool moments_only = false;
    //! All its values are small: expanded from nearer (idw_tree.h, quiet nodes).
    bool quiet = false;
};

//! What the traversal reads of a node, apart from its moments (48 bytes, so that the
//! nodes a query block visits stay in the cache).
struct IdwProbe
{
    double cx, cy, cz, radius; //!< radius: the node's opening radius
    Index child;
    bool moments_only;
};

//! A node's moments in single precision, for the far-field kernel of the default
//! weight (3, 5): a far term's relative error is then ~1e-7, far below the expansion's
//! own (theta^3), at twice the SIMD width.
struct IdwFarMoments
{
    float count, sv[3], first[3][3], second[6], second_v[3][6], trace[4];
};

} // namespace meshmorph::detail
