// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Choices that do not depend on round-off: comparisons of computed values that treat
//! values equal to about 1e-9 (relative) as ties, broken by the lowest index.
//!
//! Why: a choice made by comparing two computed numbers (the largest residual, the farthest
//! point, the nearest triangle) flips when the numbers are equal in exact arithmetic and
//! differ only in the last bits, and those bits depend on the processor (FMA, vector width,
//! OpenBLAS's kernel), the build flags and the thread count. Symmetric meshes are full of
//! such ties. A flipped discrete choice changes the result by far more than round-off (a
//! different RBF centre, a point projected onto the other slope of a surface), so it is the
//! choices, not the arithmetic, that have to be made robust.
#pragma once

#include <cmath>

#include <Eigen/Core>

namespace meshmorph
{

//! Significant bits kept by coarsened(): 2^-30 is about 1e-9, far above the round-off of
//! any value compared this way (1e-16 relative, 1e-13 after an ill-conditioned solve).
inline constexpr int tie_bits = 30;

//! \brief x rounded to tie_bits significant bits: values that differ only by round-off
//! compare equal (unless they straddle a rounding boundary, about 1 in 2^22 pairs for
//! round-off of 1e-16). Non-finite values are returned unchanged.
inline double coarsened(double x)
{
    if (!std::isfinite(x) || x == 0.0)
        return x;
    int e = 0;
    const double m = std::frexp(x, &e);
    return std::ldexp(std::round(std::ldexp(m, tie_bits)), e - tie_bits);
}

//! coarsened(a) < coarsened(b), computing the roundings only where they could matter:
//! coarsened() is monotone, so a >= b gives false, and non-negative values further apart
//! than twice its relative rounding step keep their order.
inline bool coarsened_less(double a, double b)
{
    if (!(a < b))
        return false;
    if (a >= 0.0 && a < b * (1.0 - 0x1p-28))
        return true;
    return coarsened(a) < coarsened(b);
}

//! \brief Index of the largest value of v, comparing coarsened() values; ties go to the
//! lowest index. -1 for an empty vector.
template <class Derived> Eigen::Index first_largest(const Eigen::DenseBase<Derived>& v)
{
    Eigen::Index best = -1;
    double best_value = 0.0;
    for (Eigen::Index i = 0; i < v.size(); ++i)
    {
        const double c = coarsened(v(i));
        if (best < 0 || c > best_value)
        {
            best = i;
            best_value = c;
        }
    }
    return best;
}

} // namespace meshmorph
