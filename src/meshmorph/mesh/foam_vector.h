// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: a 3-vector whose operations round exactly like OpenFOAM's `vector`.
//!
//! checkMesh's numbers are reproduced bit for bit only if every sum, product and
//! normalisation is evaluated in OpenFOAM's order (componentwise division, magSqr as
//! x*x + y*y + z*z left to right, no FMA: the quality component builds with
//! -ffp-contract=off). Eigen's expressions do not promise an order, so the checker uses
//! this small type. Not part of the public API.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph::detail
{

//! Below this many faces the checker runs serially: thread start-up and barriers cost more
//! than the work (and far more on a loaded machine, where OpenMP threads spin-wait).
inline constexpr std::int64_t parallel_threshold = 20000;

//! How many faces or cells the geometry and check loops hand a thread at a time
//! (schedule(dynamic, loop_piece)) rather than one fixed share per thread: the check before
//! a morph runs beside the fit, three or four threads on two cores, and a thread whose fixed
//! share was waiting for a core kept the other spinning at the barrier (motorBike morph, 5%
//! lift, 16 alternated runs: fit 0.373 -> 0.349 s, check after 0.076 -> 0.068 s). Every
//! piece writes its own elements and the reductions are maxima or integer counts, so the
//! results do not depend on the schedule.
inline constexpr int loop_piece = 4096;

//! flag(f) for every face, OpenMP above parallel_threshold faces: the per-face metrics that
//! flag offenders (twist, tet quality, ...) share this loop.
template <class Flag> std::vector<char> per_face_flags(Index n_faces, const Flag& flag)
{
    std::vector<char> flags(static_cast<std::size_t>(n_faces), 0);
#pragma omp parallel for schedule(dynamic, loop_piece) if (n_faces > parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
        flags[static_cast<std::size_t>(f)] = flag(f);
    return flags;
}

struct FoamVector
{
    double x = 0, y = 0, z = 0;

    double operator[](int k) const { return k == 0 ? x : (k == 1 ? y : z); }
    FoamVector& operator+=(const FoamVector& b)
    {
        x += b.x;
        y += b.y;
        z += b.z;
        return *this;
    }
    FoamVector& operator-=(const FoamVector& b)
    {
        x -= b.x;
        y -= b.y;
        z -= b.z;
        return *this;
    }
    FoamVector& operator/=(double s)
    {
        x /= s;
        y /= s;
        z /= s;
        return *this;
    }
};

inline FoamVector operator+(const FoamVector& a, const FoamVector& b)
{
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline FoamVector operator-(const FoamVector& a, const FoamVector& b)
{
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline FoamVector operator-(const FoamVector& a)
{
    return {-a.x, -a.y, -a.z};
}
inline FoamVector operator*(double s, const FoamVector& a)
{
    return {s * a.x, s * a.y, s * a.z};
}
inline FoamVector operator/(const FoamVector& a, double s)
{
    return {a.x / s, a.y / s, a.z / s};
}
//! Dot product (OpenFOAM's `&`).
inline double dot(const FoamVector& a, const FoamVector& b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
//! Cross product (OpenFOAM's `^`).
inline FoamVector cross(const FoamVector& a, const FoamVector& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
//! Area vector of the triangle (a, b, c) (OpenFOAM's triPointRef::areaNormal).
inline FoamVector tri_area_normal(const FoamVector& a, const FoamVector& b, const FoamVector& c)
{
    return 0.5 * cross(b - a, c - a);
}
inline double mag_sqr(const FoamVector& a)
{
    return a.x * a.x + a.y * a.y + a.z * a.z;
}
inline double mag(const FoamVector& a)
{
    return std::sqrt(mag_sqr(a));
}
//! Componentwise absolute value (cmptMag).
inline FoamVector cmpt_mag(const FoamVector& a)
{
    return {std::abs(a.x), std::abs(a.y), std::abs(a.z)};
}

inline FoamVector row(const Points& p, Index i)
{
    const double* d = p.data() + 3 * static_cast<std::ptrdiff_t>(i);
    return {d[0], d[1], d[2]};
}
inline void set_row(Points& p, Index i, const FoamVector& v)
{
    double* d = p.data() + 3 * static_cast<std::ptrdiff_t>(i);
    d[0] = v.x;
    d[1] = v.y;
    d[2] = v.z;
}

//! OpenFOAM's degToRad / radToDeg, in its operation order.
inline double deg_to_rad(double deg)
{
    return deg * M_PI / 180.0;
}
inline double rad_to_deg(double rad)
{
    return rad * 180.0 / M_PI;
}

//! Tetrahedron (a, b, c, d) quality as OpenFOAM's tetrahedron::quality(): signed volume over
//! the volume of the regular tetrahedron with the same circumradius (1 regular, < 0 inverted).
inline double tet_quality(const FoamVector& a, const FoamVector& b, const FoamVector& c,
                          const FoamVector& d)
{
    const FoamVector A = b - a;
    const FoamVector B = c - a;
    const FoamVector C = d - a;
    const double volume = (1.0 / 6.0) * dot(cross(A, B), C);
    const double lambda = mag_sqr(C) - dot(A, C);
    const double mu = mag_sqr(B) - dot(A, B);
    const FoamVector ba = cross(B, A);
    const FoamVector ca = cross(C, A);
    const FoamVector num = lambda * ba - mu * ca;
    const double denom = dot(C, ba);
    double radius = constants::great;
    if (std::abs(denom) >= constants::rootvsmall)
        radius = mag(0.5 * (A + num / denom));
    const double r = std::min(radius, constants::great);
    return volume / ((8.0 / (9.0 * std::sqrt(3.0))) * (r * r * r) + constants::rootvsmall);
}

} // namespace meshmorph::detail
