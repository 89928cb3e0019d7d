// SPDX-License-Identifier: GPL-3.0-or-later
// The triharmonic kernel's two ways (triharmonic8.h) and the blocked sum that mixes them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "deform_test_helpers.h"
#include "meshmorph/deform/rbf_deformation.h"
#include "meshmorph/deform/triharmonic8.h"

namespace meshmorph
{
namespace
{

using detail::double8;

double8 splat(const std::vector<double>& v, std::size_t first)
{
    double8 out;
    for (int l = 0; l < detail::lanes8; ++l)
        out[l] = v[first + std::size_t(l)];
    return out;
}

TEST(Triharmonic8, newton_steps_give_r_cubed_within_a_few_roundings_of_the_square_root)
{
    // r2 log-uniform over the range where r^3 is a normal double (far beyond what a sum
    // meets: normalised coordinates keep r2 below ~10), mantissas at random.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> mantissa(1.0, 2.0);
    std::vector<double> r2;
    for (int e = -680; e <= 680; ++e)
        for (int k = 0; k < 40; ++k)
            r2.push_back(std::ldexp(mantissa(rng), e));
    while (r2.size() % detail::lanes8 != 0)
        r2.push_back(1.0);
    double worst = 0.0;
    for (std::size_t i = 0; i < r2.size(); i += detail::lanes8)
    {
        const double8 x = splat(r2, i);
        const double8 by_newton = detail::r3_by_newton(x), by_sqrt = detail::r3_by_sqrt(x);
        for (int l = 0; l < detail::lanes8; ++l)
        {
            if (!std::isfinite(by_sqrt[l]) || by_sqrt[l] == 0.0)
            {
                // Beyond double's range either way (r^3 overflows or underflows alike).
                EXPECT_EQ(by_newton[l], by_sqrt[l]) << "r2 = " << x[l];
                continue;
            }
            worst = std::max(worst, std::abs(by_newton[l] - by_sqrt[l]) / by_sqrt[l]);
        }
    }
    // Four Newton steps end at rounding: ~3 units in the last place (6.5e-16) at most.
    EXPECT_LT(worst, 1e-15);
    EXPECT_GT(worst, 0.0); // the two ways do differ (this test compares two computations)
}

TEST(Triharmonic8, newton_steps_give_zero_at_zero_distance_and_below_the_floor)
{
    const double8 r2 = {0.0, 1e-320, 1e-301, 4.9e-324, 0.0, 0.0, 0.0, 0.0};
    const double8 r3 = detail::r3_by_newton(r2);
    for (int l = 0; l < detail::lanes8; ++l)
        EXPECT_EQ(r3[l], 0.0) << "lane " << l;
}

TEST(Triharmonic8, a_points_sum_does_not_depend_on_the_points_evaluated_with_it)
{
    // Every sixth centre goes by Newton steps: a point's value must still be the same
    // wherever it lands in a block (a -parallel rank evaluates other sets of points).
    const Points h = test::random_points(301); // centres padded: not a multiple of eight
    RbfDeformation rbf;
    rbf.fit(h, test::smooth_field(h));
    const Points x = test::random_points(1000, -0.2, 1.2, 5);
    const Points all = displacements(rbf, x);
    Points shifted(x.rows() - 37, 3);
    for (Eigen::Index i = 0; i < shifted.rows(); ++i)
        shifted.row(i) = x.row(x.rows() - 1 - i); // reversed, and fewer
    const Points some = displacements(rbf, shifted);
    for (Eigen::Index i = 0; i < shifted.rows(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_EQ(some(i, c), all(x.rows() - 1 - i, c)) << "point " << i;
}

} // namespace
} // namespace meshmorph
