// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A uniform-grid neighbour search (sorted cell keys; no dense cell array, so tiny cells
//! over a large box are fine). Used for duplicate detection and the compact Wendland kernel.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph::detail
{

class UniformGrid
{
public:
    UniformGrid() = default;
    //! \param points n x 3 \param cell cell edge length (> 0).
    UniformGrid(const Eigen::Ref<const Points>& points, double cell) : cell_(cell)
    {
        entries_.resize(static_cast<std::size_t>(points.rows()));
        for (Eigen::Index i = 0; i < points.rows(); ++i)
            entries_[std::size_t(i)] = {key(points(i, 0), points(i, 1), points(i, 2)),
                                        static_cast<std::int64_t>(i)};
        std::sort(entries_.begin(), entries_.end());
    }

    //! Calls f(index) for every point in the 27 cells around x (a superset of the points
    //! within `cell` of x), in a fixed order: cells by offset, points by index.
    template <class F> void for_each_near(double x, double y, double z, F&& f) const
    {
        any_near(x, y, z,
                 [&](Eigen::Index i)
                 {
                     f(i);
                     return false;
                 });
    }

    //! Calls f(index) for every point in the cells that the box of half-width `radius`
    //! about x overlaps (a superset of the points within `radius` of x), in the order of
    //! for_each_near. With cells much larger than the radius that is one cell nearly always,
    //! where for_each_near searches 27.
    template <class F>
    void for_each_within(double x, double y, double z, double radius, F&& f) const
    {
        const Key lo = key(x - radius, y - radius, z - radius);
        const Key hi = key(x + radius, y + radius, z + radius);
        for (std::int64_t kz = lo[2]; kz <= hi[2]; ++kz)
            for (std::int64_t ky = lo[1]; ky <= hi[1]; ++ky)
                for (std::int64_t kx = lo[0]; kx <= hi[0]; ++kx)
                    for_each_in_cell({kx, ky, kz}, f);
    }

    //! Whether pred(index) holds for a point in the 27 cells around x, trying them in
    //! for_each_near's order and stopping at the first.
    template <class P> bool any_near(double x, double y, double z, P&& pred) const
    {
        const Key c = key(x, y, z);
        for (std::int64_t dz = -1; dz <= 1; ++dz)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dx = -1; dx <= 1; ++dx)
                    if (any_in_cell({c[0] + dx, c[1] + dy, c[2] + dz}, pred))
                        return true;
        return false;
    }

private:
    using Key = std::array<std::int64_t, 3>;
    using Entry = std::pair<Key, std::int64_t>;

    //! Whether pred(index) holds for a point of cell k, trying them by index and stopping
    //! at the first.
    template <class P> bool any_in_cell(const Key& k, P& pred) const
    {
        auto it = std::lower_bound(entries_.begin(), entries_.end(), Entry{k, std::int64_t(-1)});
        for (; it != entries_.end() && it->first == k; ++it)
            if (pred(static_cast<Eigen::Index>(it->second)))
                return true;
        return false;
    }
    //! Calls f(index) for the points of cell k, by index.
    template <class F> void for_each_in_cell(const Key& k, F& f) const
    {
        auto every = [&](Eigen::Index i)
        {
            f(i);
            return false;
        };
        any_in_cell(k, every);
    }
    Key key(double x, double y, double z) const
    {
        return {static_cast<std::int64_t>(std::floor(x / cell_)),
                static_cast<std::int64_t>(std::floor(y / cell_)),
                static_cast<std::int64_t>(std::floor(z / cell_))};
    }
    double cell_ = 1.0;
    std::vector<Entry> entries_;
};

} // namespace meshmorph::detail
