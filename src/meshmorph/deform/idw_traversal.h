// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: how IdwTree walks its tree for a block of query points, shared by the
//! weighted mean (idw_tree.cpp) and its transpose (idw_tree_transpose.cpp), so that both
//! take the same far and near terms for every point.
#pragma once

#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/deform/idw_kernels.h"
#include "meshmorph/deform/idw_split.h"

namespace meshmorph::detail::idw
{

//! Loads the points of query block q (rows `order` of x) into b and lists its terms: far
//! nodes (expanded) and near leaves (summed), each with the block's lanes it applies to, in
//! the tree's depth-first order. Barnes-Hut's test is made per point (the node's opening
//! radius below theta times the distance), so a point's terms do not depend on its block.
//! False if a point needs a node written as moments only (a tree written for another
//! region).
bool load_block_terms(const Points& x, const std::vector<Index>& order, const SplitNode& q,
                      const std::vector<IdwProbe>& nodes, double theta, Block& b,
                      std::vector<Term>& far, std::vector<Term>& near);

} // namespace meshmorph::detail::idw
