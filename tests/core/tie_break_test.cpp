// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of core/tie_break.h: values that differ only by round-off tie, and ties go to the
// lowest index; values that really differ keep their order.
#include "meshmorph/core/tie_break.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

using namespace meshmorph;

TEST(TieBreak, coarsened_values_equal_but_for_round_off_compare_equal)
{
    const double x = 0.1 + 0.2; // 0.30000000000000004
    EXPECT_EQ(coarsened(x), coarsened(0.3));
    EXPECT_EQ(coarsened(std::nextafter(1.7, 2.0)), coarsened(1.7));
    EXPECT_EQ(coarsened(-2.5 * (1 + 1e-15)), coarsened(-2.5));
    // Relative differences of 1e-6 are real and stay apart.
    EXPECT_LT(coarsened(1.0), coarsened(1.0 + 1e-6));
    EXPECT_EQ(coarsened(0.0), 0.0);
    EXPECT_TRUE(std::isnan(coarsened(std::numeric_limits<double>::quiet_NaN())));
    EXPECT_EQ(coarsened(std::numeric_limits<double>::infinity()),
              std::numeric_limits<double>::infinity());
}

TEST(TieBreak, first_largest_breaks_round_off_ties_by_the_lowest_index)
{
    Eigen::VectorXd v(5);
    v << 1.0, 3.0, 0.5, 3.0 * (1 + 1e-15), 2.9;
    EXPECT_EQ(first_largest(v), 1) << "3(1 + 1e-15) ties with 3: the lower index wins";
    v[1] = 3.0 * (1 + 1e-15);
    v[3] = 3.0;
    EXPECT_EQ(first_largest(v), 1) << "whichever of the two has the last bit";
    v[4] = 3.0 * (1 + 1e-6);
    EXPECT_EQ(first_largest(v), 4) << "a real difference wins";
    EXPECT_EQ(first_largest(Eigen::VectorXd()), -1);
}

TEST(TieBreak, coarsened_less_is_the_comparison_of_the_coarsened_values)
{
    // Pairs far apart, within round-off, straddling a rounding boundary, across binades,
    // signed, zero and non-finite: the shortcut must agree with the rounding everywhere.
    std::vector<double> values = {0.0,
                                  -0.0,
                                  1e-300,
                                  0.3,
                                  0.1 + 0.2,
                                  1.0,
                                  1.0 + 1e-6,
                                  1.0 + 0x1p-30,
                                  1.0 + 0x1p-29,
                                  1.0 - 0x1p-31,
                                  2.0,
                                  3.0,
                                  -1.0,
                                  -1.0 - 1e-15,
                                  7.5e12,
                                  std::numeric_limits<double>::infinity(),
                                  -std::numeric_limits<double>::infinity(),
                                  std::numeric_limits<double>::quiet_NaN()};
    for (double x = 0.7; x < 1.5; x += 0.013)
        for (double rel : {0.0, 1e-16, 3e-10, 4.7e-10, 5e-10, 1e-9, 2e-9})
            values.push_back(x * (1 + rel));
    for (double a : values)
        for (double b : values)
            EXPECT_EQ(coarsened_less(a, b), coarsened(a) < coarsened(b)) << a << " " << b;
}
