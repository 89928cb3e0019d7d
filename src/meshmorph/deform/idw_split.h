// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: the spatial splits behind IdwTree, the source tree (midpoint cuts) and
//! the query blocks (median cuts into full blocks).
#pragma once

#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph::detail
{

//! A node of a split tree: a contiguous range of the permutation; children at child and
//! child + 1 (-1: leaf).
struct SplitNode
{
    Index begin, end, child;
};

//! The source tree: splits the points (rows of p) recursively until at most leaf_size
//! remain. order becomes the permutation that makes every node a contiguous range. Node 0
//! is the root; a node's children follow it (breadth first).
//!
//! A node is cut in the middle of its box's longest side (sliding to the median when that
//! leaves a side empty, and below depth 96, which bounds the depth for the traversal's
//! stacks). The cut follows the gaps between parts of a surface, so that a leaf does not
//! span one: on the motorBike's 57k boundary points the median cut made 10% of the leaves
//! 18 times wider than their point spacing (the midpoint cut: 11 times), and their direct
//! sums reach that much further. For the same largest error (6e-4) the median tree needed
//! theta 0.25 against 0.2 here, and 1.33x the time.
//!
//! With `group` (one flag per point) holding both values, the root is split by it first:
//! its children hold the points of group 1 and the others, each split in space below.
std::vector<SplitNode> split_sources(const Points& p, std::vector<Index>& order, Index leaf_size,
                                     const std::vector<char>& group = {});

//! The query blocks of the points `order` (rows of p), ordered by their first point; order
//! is permuted so that every block is a contiguous range of it. Median cuts along the
//! longest side, rounded to multiples of block_size, so that every block but the last is
//! full; large halves are split as OpenMP tasks (each cut depends on its points alone).
std::vector<SplitNode> query_blocks(const Points& p, std::vector<Index>& order, Index block_size);

} // namespace meshmorph::detail
