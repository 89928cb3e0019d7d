// SPDX-License-Identifier: GPL-3.0-or-later
// The inverse square roots by Newton steps (core/simd8.h, deform/idw_kernels.h): their
// accuracy over the whole range of their inputs. They replace an estimate instruction whose
// bits are the processor's, so these bounds are what the IDW and RBF sums rely on.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "meshmorph/core/simd8.h"
#include "meshmorph/deform/idw_kernels.h"

namespace meshmorph
{
namespace
{

//! Log-uniform samples 2^lo .. 2^hi, mantissas at random, a multiple of `lanes` of them.
std::vector<double> log_uniform(int lo, int hi, std::size_t lanes)
{
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> mantissa(1.0, 2.0);
    std::vector<double> x;
    for (int e = lo; e <= hi; ++e)
        for (int k = 0; k < 32; ++k)
            x.push_back(std::ldexp(mantissa(rng), e));
    while (x.size() % lanes != 0)
        x.push_back(1.0);
    return x;
}

TEST(InverseSqrt, eight_doubles_by_newton_steps_within_a_few_roundings)
{
    const std::vector<double> x = log_uniform(-1000, 1000, detail::lanes8);
    double worst = 0.0;
    for (std::size_t i = 0; i < x.size(); i += detail::lanes8)
    {
        detail::double8 v;
        for (int l = 0; l < detail::lanes8; ++l)
            v[l] = x[i + std::size_t(l)];
        const detail::double8 y = detail::inverse_sqrt8(v);
        for (int l = 0; l < detail::lanes8; ++l)
        {
            const double exact = 1.0 / std::sqrt(v[l]);
            worst = std::max(worst, std::abs(y[l] - exact) / exact);
        }
    }
    // Four steps from below 3.5e-2 end at rounding: a few units in the last place.
    EXPECT_LT(worst, 1e-15);
}

TEST(InverseSqrt, sixteen_floats_by_two_newton_steps_within_their_bound)
{
    // Two steps from below 3.5e-2 (1.75e-3 after one): 1.5 * (1.75e-3)^2 = 4.6e-6, plus
    // float rounding (~2e-7).
    const std::vector<double> x = log_uniform(-53, 100, 16); // the floor (1e-16) upwards
    double worst = 0.0;
    for (std::size_t i = 0; i < x.size(); i += 16)
    {
        detail::idw::f16 v, y;
        for (int l = 0; l < 16; ++l)
            v[l] = float(x[i + std::size_t(l)]);
        detail::idw::floored_inverse_sqrt16(v, y);
        for (int l = 0; l < 16; ++l)
        {
            const double exact =
                1.0 / std::sqrt(std::max(double(v[l]), double(detail::idw::single_floor2)));
            worst = std::max(worst, std::abs(double(y[l]) - exact) / exact);
        }
    }
    EXPECT_LT(worst, 5e-6);
    EXPECT_GT(worst, 1e-7); // two steps, not an exact root: the bound above is the one
}

TEST(InverseSqrt, sixteen_floats_below_the_floor_take_the_floors_value)
{
    detail::idw::f16 below = {}, floor_value = {}, y_below, y_floor;
    below[1] = 1e-30f;
    below[2] = 1e-17f;
    for (int l = 0; l < 16; ++l)
        floor_value[l] = detail::idw::single_floor2;
    detail::idw::floored_inverse_sqrt16(below, y_below);
    detail::idw::floored_inverse_sqrt16(floor_value, y_floor);
    for (int l = 0; l < 16; ++l)
        EXPECT_EQ(y_below[l], y_floor[l]) << "lane " << l;
}

} // namespace
} // namespace meshmorph
