// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: union-find over [0, n) (cell regions, fans of faces around a point).
#pragma once

#include <numeric>
#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph::detail
{

class DisjointSets
{
public:
    explicit DisjointSets(Index n) : parent_(static_cast<std::size_t>(n))
    {
        std::iota(parent_.begin(), parent_.end(), 0);
    }
    //! The representative of a's set (with path halving).
    Index find(Index a)
    {
        while (parent_[a] != a)
            a = parent_[a] = parent_[parent_[a]];
        return a;
    }
    //! Merge the set of representative `from` into that of representative `to`.
    void link(Index from, Index to) { parent_[from] = to; }
    //! The number of sets.
    Index count()
    {
        Index n = 0;
        for (Index a = 0; a < static_cast<Index>(parent_.size()); ++a)
            n += find(a) == a;
        return n;
    }

private:
    std::vector<Index> parent_;
};

} // namespace meshmorph::detail
