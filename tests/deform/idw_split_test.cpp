// SPDX-License-Identifier: GPL-3.0-or-later
// The IDW source tree's splits: every node a contiguous range, leaves no larger than asked,
// and with a group of points given, the group and the rest apart below the root (so that a
// tree node holds quiet sources only or none: IdwTree's quiet nodes).
#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

#include "deform_test_helpers.h"
#include "meshmorph/deform/idw_split.h"

namespace meshmorph
{

namespace
{

//! Checks the tree's structure: order is a permutation, children split their parent's
//! range in two, leaves hold at most leaf points.
void expect_a_tree(const std::vector<detail::SplitNode>& nodes, const std::vector<Index>& order,
                   Index n, Index leaf)
{
    std::vector<Index> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<Index> all(static_cast<std::size_t>(n));
    std::iota(all.begin(), all.end(), Index{0});
    EXPECT_EQ(sorted, all);
    ASSERT_FALSE(nodes.empty());
    EXPECT_EQ(nodes[0].begin, 0);
    EXPECT_EQ(nodes[0].end, n);
    for (const detail::SplitNode& node : nodes)
    {
        if (node.child < 0)
        {
            EXPECT_LE(node.end - node.begin, leaf);
            continue;
        }
        const detail::SplitNode& a = nodes[std::size_t(node.child)];
        const detail::SplitNode& b = nodes[std::size_t(node.child + 1)];
        EXPECT_EQ(a.begin, node.begin);
        EXPECT_EQ(a.end, b.begin);
        EXPECT_EQ(b.end, node.end);
        EXPECT_LT(a.begin, a.end);
        EXPECT_LT(b.begin, b.end);
    }
}

} // namespace

TEST(IdwSplit, a_group_and_the_rest_lie_apart_below_the_root)
{
    // A lifted ball on a floor; the group: the points near the contact (as a greedy fit's
    // jumps), scattered among the others in index order.
    const Index n_plane = 1500;
    Points x(n_plane + 1500, 3);
    Points plane = test::random_points(n_plane, 0.0, 1.0, 3);
    plane.col(2).setZero();
    x << plane, test::sphere_points(1500, Vector3(0.5, 0.5, 0.2001), 0.2);
    std::vector<char> quiet(std::size_t(x.rows()), 1);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        if (std::hypot(x(i, 0) - 0.5, x(i, 1) - 0.5) < 0.1 && x(i, 2) < 0.05)
            quiet[std::size_t(i)] = 0;
    const Index loud = Index(std::count(quiet.begin(), quiet.end(), 0));
    ASSERT_GT(loud, 10);

    std::vector<Index> order;
    const std::vector<detail::SplitNode> nodes = detail::split_sources(x, order, 16, quiet);
    expect_a_tree(nodes, order, x.rows(), 16);
    // The root's children: the group (quiet), then the rest.
    ASSERT_EQ(nodes[0].child, 1);
    EXPECT_EQ(nodes[2].end - nodes[2].begin, loud);
    for (const detail::SplitNode& node : nodes)
    {
        if (&node == &nodes[0])
            continue;
        const auto first = order.begin() + node.begin, last = order.begin() + node.end;
        const bool all_quiet =
            std::all_of(first, last, [&](Index i) { return quiet[std::size_t(i)] != 0; });
        const bool none_quiet =
            std::none_of(first, last, [&](Index i) { return quiet[std::size_t(i)] != 0; });
        EXPECT_TRUE(all_quiet || none_quiet) << "node " << (&node - nodes.data());
    }

    // No group, or a group of all: split in space from the root, as before.
    std::vector<Index> plain_order, all_order;
    const auto plain = detail::split_sources(x, plain_order, 16);
    const auto all = detail::split_sources(x, all_order, 16, std::vector<char>(quiet.size(), 1));
    expect_a_tree(plain, plain_order, x.rows(), 16);
    EXPECT_EQ(plain_order, all_order);
    EXPECT_EQ(plain.size(), all.size());
}

} // namespace meshmorph
