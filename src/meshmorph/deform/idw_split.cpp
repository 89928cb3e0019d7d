// SPDX-License-Identifier: GPL-3.0-or-later
// The source tree and the query blocks of the IDW evaluation (see the header).
#include "meshmorph/deform/idw_split.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace meshmorph::detail
{

namespace
{

//! The bounding box of the points order[begin..end) (rows of p) and its longest axis.
int longest_axis(const Points& p, const std::vector<Index>& order, Index begin, Index end,
                 Vector3& lo, Vector3& hi)
{
    lo = Vector3::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    for (Index i = begin; i < end; ++i)
    {
        lo = lo.cwiseMin(p.row(order[std::size_t(i)]).transpose());
        hi = hi.cwiseMax(p.row(order[std::size_t(i)]).transpose());
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    return axis;
}

//! Puts the `half` points of order[begin..end) lowest along axis first (ties by index, so
//! that the cut does not depend on the order the points come in); returns the cut.
Index median_cut(const Points& p, std::vector<Index>& order, Index begin, Index end, int axis,
                 Index half)
{
    const auto first = order.begin() + begin, last = order.begin() + end;
    std::nth_element(first, first + half, last,
                     [&](Index a, Index b)
                     { return p(a, axis) < p(b, axis) || (p(a, axis) == p(b, axis) && a < b); });
    return begin + half;
}

//! A query point with its row, so that the median cuts compare and move contiguous memory
//! (the rows of p, looked up through order, are scattered: on the motorBike's 406k points
//! the cuts took 1.5 times as long).
struct QueryPoint
{
    double c[3];
    Index row;
};

//! The longest axis of the bounding box of q[begin..end).
int longest_axis(const std::vector<QueryPoint>& q, Index begin, Index end)
{
    Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity());
    Vector3 hi = -lo;
    for (Index i = begin; i < end; ++i)
    {
        const Vector3 x(q[std::size_t(i)].c[0], q[std::size_t(i)].c[1], q[std::size_t(i)].c[2]);
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    return axis;
}

//! Appends the query blocks of q[begin..end) to `blocks`: median cuts along the longest
//! side (ties by row, as median_cut), rounded to a multiple of block_size so that every
//! block but the last is full (blocks then fill their SIMD lanes: with halves, they held 21
//! points on average). The halves of a large node are split as OpenMP tasks; each cut
//! depends on its points alone.
void split_blocks(std::vector<QueryPoint>& q, Index begin, Index end, Index block_size,
                  std::vector<SplitNode>& blocks)
{
    const Index n = end - begin;
    if (n <= block_size)
    {
#pragma omp critical(meshmorph_idw_blocks)
        blocks.push_back({begin, end, -1});
        return;
    }
    const int axis = longest_axis(q, begin, end);
    const Index split = begin + block_size * ((n / block_size + 1) / 2);
    std::nth_element(q.begin() + begin, q.begin() + split, q.begin() + end,
                     [axis](const QueryPoint& a, const QueryPoint& b) {
                         return a.c[axis] < b.c[axis] || (a.c[axis] == b.c[axis] && a.row < b.row);
                     });
    constexpr Index task_size = 16384; // below this a task costs more than it saves
#pragma omp task default(shared) if (n > task_size)
    split_blocks(q, begin, split, block_size, blocks);
    split_blocks(q, split, end, block_size, blocks);
#pragma omp taskwait
}

} // namespace

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
std::vector<SplitNode> split_sources(const Points& p, std::vector<Index>& order, Index leaf_size,
                                     const std::vector<char>& group)
{
    constexpr int deepest_midpoint = 96;
    order.resize(static_cast<std::size_t>(p.rows()));
    std::iota(order.begin(), order.end(), Index{0});
    std::vector<SplitNode> nodes{{0, static_cast<Index>(p.rows()), -1}};
    std::vector<int> depth{0};
    if (!group.empty())
    {
        // The root's children: the points of group 1, then the others (each in index order).
        const Index split = static_cast<Index>(
            std::stable_partition(order.begin(), order.end(),
                                  [&](Index a) { return group[std::size_t(a)] != 0; }) -
            order.begin());
        if (split > 0 && split < static_cast<Index>(p.rows()))
        {
            nodes[0].child = 1;
            nodes.push_back({0, split, -1});
            nodes.push_back({split, static_cast<Index>(p.rows()), -1});
            depth.push_back(1);
            depth.push_back(1);
        }
    }
    for (std::size_t k = 0; k < nodes.size(); ++k)
    {
        const SplitNode node = nodes[k];
        if (node.end - node.begin <= leaf_size || node.child >= 0)
            continue;
        Vector3 lo, hi;
        const int axis = longest_axis(p, order, node.begin, node.end, lo, hi);
        Index split = -1;
        if (depth[k] < deepest_midpoint)
        {
            const double cut = 0.5 * (lo[axis] + hi[axis]);
            split = static_cast<Index>(
                std::stable_partition(order.begin() + node.begin, order.begin() + node.end,
                                      [&](Index a) { return p(a, axis) < cut; }) -
                order.begin());
            if (split == node.begin || split == node.end)
                split = -1;
        }
        if (split < 0)
            split = median_cut(p, order, node.begin, node.end, axis, (node.end - node.begin) / 2);
        nodes[k].child = static_cast<Index>(nodes.size());
        nodes.push_back({node.begin, split, -1});
        nodes.push_back({split, node.end, -1});
        depth.push_back(depth[k] + 1);
        depth.push_back(depth[k] + 1);
    }
    return nodes;
}

//! The query blocks of the points `order` (rows of p), ordered by their first point; order
//! is permuted so that every block is a contiguous range of it.
std::vector<SplitNode> query_blocks(const Points& p, std::vector<Index>& order, Index block_size)
{
    const Index n = static_cast<Index>(order.size());
    std::vector<QueryPoint> q(order.size());
    for (std::size_t i = 0; i < q.size(); ++i)
        q[i] = {{p(order[i], 0), p(order[i], 1), p(order[i], 2)}, order[i]};
    std::vector<SplitNode> blocks;
#pragma omp parallel if (n > 4 * 16384)
#pragma omp single
    split_blocks(q, 0, n, block_size, blocks);
    for (std::size_t i = 0; i < q.size(); ++i)
        order[i] = q[i].row;
    std::sort(blocks.begin(), blocks.end(),
              [](const SplitNode& a, const SplitNode& b) { return a.begin < b.begin; });
    return blocks;
}

} // namespace meshmorph::detail
