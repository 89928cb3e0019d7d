// SPDX-License-Identifier: GPL-3.0-or-later
// jump_points against the pairwise definition, on data with a jump and on smooth data;
// jump_band's width: the motion over the slope, or the floor of the moving points' extent.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "deform_test_helpers.h"
#include "meshmorph/deform/jump_detection.h"

namespace meshmorph
{

namespace
{

//! The definition, pair by pair.
std::vector<char> brute_force(const Points& x, const Eigen::MatrixXd& v, double slope, double reach)
{
    std::vector<char> flag(std::size_t(x.rows()), 0);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        for (Eigen::Index j = 0; j < x.rows(); ++j)
        {
            const double d = (x.row(i) - x.row(j)).norm();
            if (j != i && d <= reach && (v.row(i) - v.row(j)).norm() > slope * d)
                flag[std::size_t(i)] = 1;
        }
    return flag;
}

} // namespace

TEST(JumpDetection, equals_the_pairwise_definition_where_a_lifted_ball_meets_a_fixed_floor)
{
    // A sphere lifted by 0.05 touching a fixed plane, and a rotated box around (smooth).
    Points plane = test::random_points(1500, 0.0, 1.0, 3);
    plane.col(2).setZero();
    const Points ball = test::sphere_points(1500, Vector3(0.5, 0.5, 0.2001), 0.2);
    Points x(plane.rows() + ball.rows(), 3);
    x << plane, ball;
    Eigen::MatrixXd v = Eigen::MatrixXd::Zero(x.rows(), 3);
    v.bottomRows(ball.rows()).col(2).setConstant(0.05);
    for (const double slope : {0.5, 1.0, 4.0})
        for (const double reach : {0.02, 0.1, 0.5})
        {
            Index count = -1;
            const std::vector<char> flag = detail::jump_points(x, v, slope, reach, count);
            const std::vector<char> expected = brute_force(x, v, slope, reach);
            EXPECT_EQ(flag, expected) << "slope " << slope << ", reach " << reach;
            EXPECT_EQ(count, Index(std::count(expected.begin(), expected.end(), 1)));
        }
    Index count = 0;
    detail::jump_points(x, v, 1.0, 0.1, count);
    EXPECT_GT(count, 0);             // the contact is found ...
    EXPECT_LT(count, x.rows() / 10); // ... and nothing else
}

TEST(JumpDetection, finds_none_in_a_rotation_slower_than_the_slope)
{
    const Points x = test::random_points(3000, -1.0, 1.0, 5);
    Eigen::MatrixXd v(x.rows(), 3);
    const double omega = 0.3; // |v_i - v_j| = omega |x_i - x_j| in the plane: below slope 1
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        v.row(i) << -omega * x(i, 1), omega * x(i, 0), 0.0;
    Index count = -1;
    const std::vector<char> flag = detail::jump_points(x, v, 1.0, 0.5, count);
    EXPECT_EQ(count, 0);
    EXPECT_EQ(flag, brute_force(x, v, 1.0, 0.5));
    // Faster than the slope: every point jumps against some neighbour.
    detail::jump_points(x, v, 0.2, 0.5, count);
    EXPECT_EQ(count, x.rows());
}

TEST(JumpDetection, switched_off_by_a_zero_slope_or_reach)
{
    const Points x = test::random_points(100, 0.0, 1.0, 7);
    const Eigen::MatrixXd v = Eigen::MatrixXd::Random(x.rows(), 3);
    Index count = -1;
    EXPECT_EQ(detail::jump_points(x, v, 0.0, 1.0, count), std::vector<char>(100, 0));
    EXPECT_EQ(count, 0);
    EXPECT_EQ(detail::jump_points(x, v, 1.0, 0.0, count), std::vector<char>(100, 0));
    EXPECT_EQ(count, 0);
}

TEST(JumpBand, is_the_motion_over_the_slope_but_no_narrower_than_the_floor_of_the_moving_extent)
{
    // Fixed points over [0, 4]^3, and a moving box [1, 2] x [1, 3] x [1, 1.5] (diagonal 2.29).
    Points x = test::random_points(2000, 0.0, 4.0, 11);
    const Points box = test::random_points(1000, 0.0, 1.0, 13);
    const Index n_fixed = x.rows();
    x.conservativeResize(n_fixed + box.rows() + 2, 3);
    for (Eigen::Index i = 0; i < box.rows(); ++i)
        x.row(n_fixed + i) << 1.0 + box(i, 0), 1.0 + 2.0 * box(i, 1), 1.0 + 0.5 * box(i, 2);
    x.row(x.rows() - 2) << 1.0, 1.0, 1.0; // the box's corners, so its extent is known
    x.row(x.rows() - 1) << 2.0, 3.0, 1.5;
    const double extent = std::sqrt(1.0 + 4.0 + 0.25);
    Eigen::MatrixXd v = Eigen::MatrixXd::Zero(x.rows(), 3);
    // A round-off displacement on a far fixed point is no motion (1e-6 of the largest).
    v(0, 0) = 1e-12;
    for (const double lift : {0.01, 0.4})
    {
        v.bottomRows(box.rows() + 2).col(2).setConstant(lift);
        const detail::JumpBand band = detail::jump_band(x, v, 2.0, 0.025);
        EXPECT_NEAR(band.extent, extent, 1e-12);
        const double width = std::max(lift / 2.0, 0.025 * extent);
        EXPECT_NEAR(band.width, width, 1e-12 * width) << "lift " << lift;
        EXPECT_NEAR(band.slope, lift / width, 1e-12 * lift / width) << "lift " << lift;
    }
    // A small lift sits on the floor (0.057 wide); a large one is bound by the slope (0.2).
    EXPECT_NEAR(detail::jump_band(x, v, 2.0, 0.025).width, 0.2, 1e-12);
    v.bottomRows(box.rows() + 2).col(2).setConstant(0.01);
    EXPECT_NEAR(detail::jump_band(x, v, 2.0, 0.025).width, 0.025 * extent, 1e-12);
    // No floor: the slope alone. No slope, or no motion: no band.
    EXPECT_NEAR(detail::jump_band(x, v, 2.0, 0.0).slope, 2.0, 1e-15);
    EXPECT_EQ(detail::jump_band(x, v, 0.0, 0.025).slope, 0.0);
    EXPECT_EQ(detail::jump_band(x, Eigen::MatrixXd::Zero(x.rows(), 3), 2.0, 0.025).slope, 0.0);
}

} // namespace meshmorph
