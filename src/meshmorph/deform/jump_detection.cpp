// SPDX-License-Identifier: GPL-3.0-or-later
// Points where scattered data jumps: cell pairs first, point pairs only where values differ.
#include "meshmorph/deform/jump_detection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "meshmorph/core/tie_break.h"

namespace meshmorph::detail
{

namespace
{

using CellKey = std::array<std::int64_t, 3>;

//! The points of one grid cell (a range of the sorted order), their box and a ball around
//! their values.
struct Cell
{
    CellKey key;
    std::size_t begin = 0, end = 0;
    Eigen::Vector3d lo, hi;
    Eigen::Vector3d value_mid;
    double value_radius = 0.0;
};

CellKey cell_key(const Points& x, Eigen::Index i, double size)
{
    return {static_cast<std::int64_t>(std::floor(x(i, 0) / size)),
            static_cast<std::int64_t>(std::floor(x(i, 1) / size)),
            static_cast<std::int64_t>(std::floor(x(i, 2) / size))};
}

Cell make_cell(const Points& x, const Eigen::MatrixXd& v, const std::vector<Eigen::Index>& order,
               std::size_t begin, std::size_t end, const CellKey& key)
{
    Cell c;
    c.key = key;
    c.begin = begin;
    c.end = end;
    c.lo = c.hi = x.row(order[begin]).transpose();
    Eigen::Vector3d vlo = v.row(order[begin]).transpose(), vhi = vlo;
    for (std::size_t k = begin; k < end; ++k)
    {
        const Eigen::Vector3d p = x.row(order[k]).transpose(), q = v.row(order[k]).transpose();
        c.lo = c.lo.cwiseMin(p);
        c.hi = c.hi.cwiseMax(p);
        vlo = vlo.cwiseMin(q);
        vhi = vhi.cwiseMax(q);
    }
    c.value_mid = 0.5 * (vlo + vhi);
    c.value_radius = 0.5 * (vhi - vlo).norm();
    return c;
}

//! The cells of size `size` holding the points, sorted by key; `order` lists the points
//! cell by cell.
std::vector<Cell> sorted_cells(const Points& x, const Eigen::MatrixXd& v, double size,
                               std::vector<Eigen::Index>& order)
{
    std::vector<std::pair<CellKey, Eigen::Index>> entries(static_cast<std::size_t>(x.rows()));
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        entries[std::size_t(i)] = {cell_key(x, i, size), i};
    std::sort(entries.begin(), entries.end());
    order.resize(entries.size());
    for (std::size_t k = 0; k < entries.size(); ++k)
        order[k] = entries[k].second;
    std::vector<Cell> cells;
    for (std::size_t k = 0; k < entries.size();)
    {
        std::size_t e = k;
        while (e < entries.size() && entries[e].first == entries[k].first)
            ++e;
        cells.push_back(make_cell(x, v, order, k, e, entries[k].first));
        k = e;
    }
    return cells;
}

double box_gap(const Cell& a, const Cell& b)
{
    const Eigen::Vector3d gap = (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(0.0);
    return gap.norm();
}

//! True when point i has a jump partner among the points of cell b.
bool jumps_into(const Points& x, const Eigen::MatrixXd& v, const std::vector<Eigen::Index>& order,
                Eigen::Index i, const Cell& b, double slope2, double reach2)
{
    for (std::size_t k = b.begin; k < b.end; ++k)
    {
        const Eigen::Index j = order[k];
        const double d2 = (x.row(i) - x.row(j)).squaredNorm();
        // coarsened(d2) <= coarsened(reach2), coarsened(|dv|^2) > coarsened(slope2 d2).
        if (j != i && !coarsened_less(reach2, d2) &&
            coarsened_less(slope2 * d2, (v.row(i) - v.row(j)).squaredNorm()))
            return true;
    }
    return false;
}

} // namespace

std::vector<char> jump_points(const Points& x, const Eigen::MatrixXd& values, double slope,
                              double reach, Index& count)
{
    std::vector<char> flag(static_cast<std::size_t>(x.rows()), 0);
    count = 0;
    if (!(slope > 0.0) || !(reach > 0.0) || x.rows() < 2)
        return flag;
    std::vector<Eigen::Index> order;
    // Cells of reach / 2: every partner within reach lies in the 5 x 5 x 5 block around.
    const std::vector<Cell> cells = sorted_cells(x, values, 0.5 * reach, order);
    const double slope2 = slope * slope, reach2 = reach * reach;
    // The cells of one (x, y) column are consecutive in key order: one search per column.
    const auto column = [&](std::int64_t kx, std::int64_t ky, std::int64_t z_lo)
    {
        return std::lower_bound(cells.begin(), cells.end(), CellKey{kx, ky, z_lo},
                                [](const Cell& c, const CellKey& k) { return c.key < k; });
    };
    Index flagged = 0;
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : flagged)
    for (std::size_t ca = 0; ca < cells.size(); ++ca)
    {
        const Cell& a = cells[ca];
        for (std::int64_t dx = -2; dx <= 2; ++dx)
            for (std::int64_t dy = -2; dy <= 2; ++dy)
                for (auto b = column(a.key[0] + dx, a.key[1] + dy, a.key[2] - 2);
                     b != cells.end() && b->key[0] == a.key[0] + dx && b->key[1] == a.key[1] + dy &&
                     b->key[2] <= a.key[2] + 2;
                     ++b)
                {
                    const double gap = box_gap(a, *b);
                    const double most =
                        (a.value_mid - b->value_mid).norm() + a.value_radius + b->value_radius;
                    // With a margin far above round-off: a pair the (coarsened) test could
                    // flag is never skipped here, whatever the processor's rounding.
                    // most == 0: every value of both cells is the same (a rigid part's
                    // points), so no pair differs at all; the test below would let through
                    // the pairs of a cell with itself (gap 0).
                    if (gap > reach * (1 + 1e-6) || most < slope * gap * (1 - 1e-6) || most == 0.0)
                        continue; // no pair of these cells can jump
                    for (std::size_t k = a.begin; k < a.end; ++k)
                    {
                        const Eigen::Index i = order[k];
                        if (!flag[std::size_t(i)] &&
                            jumps_into(x, values, order, i, *b, slope2, reach2))
                        {
                            flag[std::size_t(i)] = 1;
                            ++flagged;
                        }
                    }
                }
    }
    count = flagged;
    return flag;
}

JumpBand jump_band(const Points& x, const Eigen::MatrixXd& values, double max_slope,
                   double min_width)
{
    JumpBand band;
    const Eigen::VectorXd size = values.rowwise().norm();
    const double largest = size.size() > 0 ? size.maxCoeff() : 0.0;
    if (!(max_slope > 0.0) || !(largest > 0.0))
        return band;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        if (size[i] > 1e-6 * largest)
        {
            lo = lo.cwiseMin(x.row(i).transpose());
            hi = hi.cwiseMax(x.row(i).transpose());
        }
    band.extent = (hi - lo).norm();
    band.width = std::max(largest / max_slope, min_width * band.extent);
    band.slope = largest / band.width;
    return band;
}

std::vector<char> jump_constraints(const Points& x, const Eigen::MatrixXd& values, double max_slope,
                                   double min_width, JumpBand& band, Index& count)
{
    count = 0;
    band = {};
    if (x.rows() < 2)
        return {};
    band = jump_band(x, values, max_slope, min_width);
    if (!(band.slope > 0.0))
        return {};
    const double extent = (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
    return jump_points(x, values, band.slope, std::min(2.0 * band.width, extent / 20.0), count);
}

} // namespace meshmorph::detail
