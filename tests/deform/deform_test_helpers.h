// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Point sets and fields shared by the deform tests (header-only).
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph::test
{

//! n points uniformly random in [lo, hi]^3 (fixed seed: reproducible).
inline Points random_points(Eigen::Index n, double lo = 0.0, double hi = 1.0, unsigned seed = 7)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(lo, hi);
    Points p(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            p(i, c) = u(gen);
    return p;
}

//! n points on a sphere (Fibonacci spiral) of the given centre and radius.
inline Points sphere_points(Eigen::Index n, const Vector3& centre, double radius)
{
    Points p(n, 3);
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (Eigen::Index i = 0; i < n; ++i)
    {
        const double z = 1.0 - 2.0 * (double(i) + 0.5) / double(n);
        const double r = std::sqrt(1.0 - z * z);
        const double t = golden * double(i);
        p.row(i) = (centre + radius * Vector3(r * std::cos(t), r * std::sin(t), z)).transpose();
    }
    return p;
}

//! Displacements of the affine map x -> L x + t, i.e. (L - I) x + t, for every row.
inline Points affine_displacements(const Points& x, const Eigen::Matrix3d& L, const Vector3& t)
{
    Points d(x.rows(), 3);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        d.row(i) = ((L - Eigen::Matrix3d::Identity()) * x.row(i).transpose() + t).transpose();
    return d;
}

//! A smooth, non-polynomial field.
inline Points smooth_field(const Points& x)
{
    Points d(x.rows(), 3);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
    {
        const double a = x(i, 0), b = x(i, 1), c = x(i, 2);
        d(i, 0) = 0.1 * std::sin(2.0 * a + b);
        d(i, 1) = 0.05 * std::cos(3.0 * b) * c;
        d(i, 2) = 0.08 * std::exp(-((a - 0.5) * (a - 0.5) + (b - 0.5) * (b - 0.5)));
    }
    return d;
}

//! What a global fit leaves for its IDW correction: values within 1e-2 everywhere (a smooth
//! field scaled down), except a few large ones (0.6 in z) on the points with z below
//! `jump_below`, like the jumps under the motorBike's tyres.
inline Points residual_like_field(const Points& x, double jump_below)
{
    Points r = smooth_field(x) * 0.1;
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        if (x(i, 2) < jump_below)
            r(i, 2) = -0.6;
    return r;
}

//! Per row of residual_like_field(): 1 (quiet) for the small values, 0 for the large ones.
inline std::vector<char> small_values(const Points& r)
{
    std::vector<char> quiet(std::size_t(r.rows()));
    for (Eigen::Index i = 0; i < r.rows(); ++i)
        quiet[std::size_t(i)] = r.row(i).norm() < 0.1;
    return quiet;
}

inline double max_norm(const Points& d)
{
    double m = 0.0;
    for (Eigen::Index i = 0; i < d.rows(); ++i)
        m = std::max(m, d.row(i).norm());
    return m;
}

//! Handles clustered in a small region of a large domain, as the cells near a body in a
//! snappyHexMesh case: 400 in a box of 1e-2, 8 of them spread over [-1, 1]. The
//! triharmonic system's condition is ~5e12; iterative refinement fits it to ~1e-8 of the
//! largest displacement.
struct ClusteredHandles
{
    Points h;
    Points d;
    ClusteredHandles() : h(random_points(400, 0.0, 1e-2, 3))
    {
        h.topRows(8) = random_points(8, -1.0, 1.0, 4);
        d = smooth_field(h * 50.0);
    }
};

} // namespace meshmorph::test
