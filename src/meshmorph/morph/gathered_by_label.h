// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Items gathered from every rank of a -parallel run, one per label of the undecomposed
//! mesh: a point on a processor patch arrives once from each rank that holds it.
#pragma once

#include <algorithm>
#include <vector>

namespace meshmorph::morph
{

//! \brief Every rank's items (by rank, as Communicator::gather_values returns them) sorted by
//! their `label`, each label once: the lowest rank's copy (a stable sort keeps rank order).
template <class T> std::vector<T> sorted_unique(const std::vector<std::vector<T>>& all)
{
    std::vector<T> out;
    for (const std::vector<T>& rank : all)
        out.insert(out.end(), rank.begin(), rank.end());
    std::stable_sort(out.begin(), out.end(),
                     [](const T& a, const T& b) { return a.label < b.label; });
    out.erase(std::unique(out.begin(), out.end(),
                          [](const T& a, const T& b) { return a.label == b.label; }),
              out.end());
    return out;
}

} // namespace meshmorph::morph
