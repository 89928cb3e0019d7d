// SPDX-License-Identifier: GPL-3.0-or-later
// first_nonpositive_step: the first root of cubics with known roots, including a double root
// that touches zero between samples, a root beyond the limit and no root at all.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "meshmorph/core/cubic_first_root.h"

namespace meshmorph
{
namespace
{

constexpr double inf = std::numeric_limits<double>::infinity();

//! -(t - r1)(t - r2)(t - r3) (positive at 0 for positive roots).
Cubic negated_roots(double r1, double r2, double r3)
{
    return {r1 * r2 * r3, -(r1 * r2 + r1 * r3 + r2 * r3), r1 + r2 + r3, -1.0};
}

TEST(CubicFirstRoot, finds_the_smallest_of_three_positive_roots)
{
    EXPECT_NEAR(first_nonpositive_step(negated_roots(1, 2, 3), inf), 1.0, 1e-12);
    EXPECT_NEAR(first_nonpositive_step(negated_roots(0.5, 0.6, 10), inf), 0.5, 1e-12);
    EXPECT_NEAR(first_nonpositive_step(negated_roots(3, 1e-3, 7), inf), 1e-3, 1e-15);
}

TEST(CubicFirstRoot, finds_a_double_root_where_the_cubic_only_touches_zero)
{
    // (t - 2)^2: zero at t = 2 alone, positive on both sides.
    EXPECT_NEAR(first_nonpositive_step({4.0, -4.0, 1.0, 0.0}, inf), 2.0, 1e-6);
    // (t - 2)^2 (t + 1) = t^3 - 3 t^2 + 4: a cubic touching zero at 2.
    EXPECT_NEAR(first_nonpositive_step({4.0, 0.0, -3.0, 1.0}, inf), 2.0, 1e-6);
}

TEST(CubicFirstRoot, ignores_roots_beyond_the_limit_and_cubics_that_stay_positive)
{
    EXPECT_EQ(first_nonpositive_step(negated_roots(1, 2, 3), 0.999), inf);
    EXPECT_NEAR(first_nonpositive_step(negated_roots(1, 2, 3), 1.0), 1.0, 1e-12);
    EXPECT_EQ(first_nonpositive_step({1.0, 0.0, 1.0, 0.0}, inf), inf);  // 1 + t^2
    EXPECT_EQ(first_nonpositive_step({1.0, 2.0, 0.0, 0.5}, inf), inf);  // grows
    EXPECT_EQ(first_nonpositive_step({1.0, 0.0, 0.0, 0.0}, inf), inf);  // constant
    EXPECT_EQ(first_nonpositive_step({1.0, -1.0, 0.0, 0.0}, 0.5), inf); // 1 - t
}

TEST(CubicFirstRoot, is_exact_on_lines_and_parabolas_at_any_scale)
{
    EXPECT_NEAR(first_nonpositive_step({1e-12, -1e-12, 0.0, 0.0}, inf), 1.0, 1e-12);
    EXPECT_NEAR(first_nonpositive_step({1e-18, 0.0, -1e-6, 0.0}, inf), 1e-6, 1e-18);
    EXPECT_NEAR(first_nonpositive_step({1e3, -1e9, 0.0, 0.0}, inf), 1e-6, 1e-18);
}

} // namespace
} // namespace meshmorph
