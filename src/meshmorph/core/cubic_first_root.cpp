// SPDX-License-Identifier: GPL-3.0-or-later
// The first non-positive step of a cubic: split at the critical points, solve on the first
// monotone piece whose end is non-positive.
#include "meshmorph/core/cubic_first_root.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace meshmorph
{

namespace
{

//! The positive roots of p'(t) = c1 + 2 c2 t + 3 c3 t^2, ascending (at most two), below
//! `end`. The quadratic formula in its cancellation-free form.
int critical_points(const Cubic& p, double end, std::array<double, 2>& out)
{
    const double a = 3.0 * p[3], b = 2.0 * p[2], c = p[1];
    std::array<double, 2> roots{};
    int n = 0;
    if (a == 0.0)
    {
        if (b != 0.0)
            roots[n++] = -c / b;
    }
    else
    {
        const double disc = b * b - 4.0 * a * c;
        if (disc >= 0.0)
        {
            const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
            roots[n++] = q / a;
            if (q != 0.0)
                roots[n++] = c / q;
        }
    }
    int kept = 0;
    for (int k = 0; k < n; ++k)
        if (std::isfinite(roots[k]) && roots[k] > 0.0 && roots[k] < end)
            out[kept++] = roots[k];
    if (kept == 2 && out[1] < out[0])
        std::swap(out[0], out[1]);
    return kept;
}

//! Cauchy's bound: every real root of p lies in |t| < 1 + max_k |c_k / c_lead|.
double root_bound(const Cubic& p)
{
    int lead = 3;
    while (lead > 0 && p[std::size_t(lead)] == 0.0)
        --lead;
    if (lead == 0)
        return 0.0; // a positive constant: no root
    double ratio = 0.0;
    for (int k = 0; k < lead; ++k)
        ratio = std::max(ratio, std::abs(p[std::size_t(k)] / p[std::size_t(lead)]));
    return 1.0 + ratio;
}

//! p(lo) > 0 >= p(hi), p monotone on [lo, hi]: the first non-positive t, by the Illinois
//! variant of regula falsi (superlinear; the bracket always holds the root, so it cannot
//! miss it as Newton's method could), to a relative 1e-13.
double bisect(const Cubic& p, double lo, double hi)
{
    double f_lo = evaluate_cubic(p, lo), f_hi = evaluate_cubic(p, hi);
    int side = 0; // which end was kept last: halve its value when kept twice (Illinois)
    for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i)
    {
        double t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        if (!(t > lo && t < hi))
            t = 0.5 * (lo + hi);
        const double f = evaluate_cubic(p, t);
        if (f > 0.0)
        {
            lo = t, f_lo = f;
            if (side == -1)
                f_hi *= 0.5;
            side = -1;
        }
        else
        {
            hi = t, f_hi = f;
            if (side == 1)
                f_lo *= 0.5;
            side = 1;
        }
    }
    return hi;
}

} // namespace

double first_nonpositive_step(const Cubic& p, double limit)
{
    constexpr double none = std::numeric_limits<double>::infinity();
    const double end = std::min(limit, root_bound(p));
    if (!(end > 0.0))
        return none;
    std::array<double, 3> ends{};
    std::array<double, 2> critical{};
    const int n = critical_points(p, end, critical);
    std::copy(critical.begin(), critical.begin() + n, ends.begin());
    ends[std::size_t(n)] = end;
    double lo = 0.0;
    for (int k = 0; k <= n; ++k)
    {
        const double hi = ends[std::size_t(k)];
        if (evaluate_cubic(p, hi) <= 0.0)
            return bisect(p, lo, hi);
        lo = hi;
    }
    return none;
}

} // namespace meshmorph
