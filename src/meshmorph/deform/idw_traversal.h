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

//! What a block's forward sums read: the tree's arrays and its kernels' choice.
struct ForwardSums
{
    const SourceArrays& sources;
    const IdwProbe* probes;
    const IdwFarMoments* moments;
    const SourcesSingle& sources_single;
    float beta;
    bool single;             //!< the default weight with a tree: single-precision kernels
    const Weight35& w35;     //!< the default weight, in double precision
    const WeightGeneral& wg; //!< any other weight
    bool default_weight;
};

//! N, D and the coincidences of a block's points over its terms, with the kernels the
//! weighted mean sums them with.
inline void add_block_sums(const BlockTerms& terms, const ForwardSums& forward, Block& b,
                           FarSums& fs)
{
    b.clear_sums();
    if (forward.single)
        add_terms_single(terms, forward.probes, forward.moments, forward.sources_single,
                         forward.beta, b, fs);
    else if (forward.default_weight)
        add_terms(terms, forward.sources, forward.w35, b);
    else
        add_terms(terms, forward.sources, forward.wg, b);
}

} // namespace meshmorph::detail::idw
