// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: FoamVector's operations on eight lanes at once, for the per-face loops of
//! the geometry and the checks over a mesh's quads (94% of a snappyHexMesh mesh's faces).
//! A kernel is written once as a template over the vector type (FoamVector or Vector8) and
//! the scalar type (double or double8), so that both paths share one sequence of operations.
//! Each lane runs FoamVector's operations in their order (and the quality and mesh
//! components build with -ffp-contract=off), so a lane's result is bit for bit the one of
//! the scalar code: an operation rounds the same in a vector register as in a scalar one.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/simd8.h"
#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph::detail
{

//! std::max and std::abs by one name for a double and for eight lanes, so that a kernel
//! written once serves both (lane-wise: b where a < b, else a; the sign bit cleared).
inline double lane_max(double a, double b)
{
    return std::max(a, b);
}
inline double8 lane_max(const double8& a, const double8& b)
{
    return a < b ? b : a;
}
inline double lane_abs(double a)
{
    return std::abs(a);
}
inline double8 lane_abs(const double8& a)
{
    return reinterpret_cast<double8>(reinterpret_cast<bits8>(a) & 0x7fffffffffffffffULL);
}

//! A 3-vector of eight lanes.
struct Vector8
{
    double8 x, y, z;
};
inline Vector8 operator+(const Vector8& a, const Vector8& b)
{
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vector8 operator-(const Vector8& a, const Vector8& b)
{
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vector8 operator*(const double8& s, const Vector8& a)
{
    return {s * a.x, s * a.y, s * a.z};
}
inline Vector8 operator/(const Vector8& a, const double8& s)
{
    return {a.x / s, a.y / s, a.z / s};
}
inline Vector8 operator/(const Vector8& a, double s)
{
    return {a.x / s, a.y / s, a.z / s};
}
inline double8 dot(const Vector8& a, const Vector8& b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vector8 cross(const Vector8& a, const Vector8& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double8 mag(const Vector8& a)
{
    return sqrt8(a.x * a.x + a.y * a.y + a.z * a.z);
}

//! Rows rows[0..7] of a 3-column array.
inline Vector8 gather8(const Points& p, const Index* rows)
{
    // Through arrays: GCC 12 takes lane stores into an unset vector for reads of it.
    std::array<double, lanes8> x, y, z;
    for (std::size_t l = 0; l < x.size(); ++l)
    {
        const double* d = p.data() + 3 * std::ptrdiff_t(rows[l]);
        x[l] = d[0];
        y[l] = d[1];
        z[l] = d[2];
    }
    return {load8(x.data()), load8(y.data()), load8(z.data())};
}

//! Vertex k of each of the eight faces `faces` (each with more than k vertices).
inline Vector8 face_vertex8(const PolyMesh& mesh, const Index* faces, int k)
{
    std::array<Index, lanes8> labels;
    for (int l = 0; l < lanes8; ++l)
        labels[std::size_t(l)] =
            mesh.faces.values[std::size_t(mesh.faces.offsets[std::size_t(faces[l])] + k)];
    return gather8(mesh.points, labels.data());
}

//! Lane l of v.
inline FoamVector lane(const Vector8& v, int l)
{
    return {v.x[l], v.y[l], v.z[l]};
}

//! Faces per range of for_quads_in_range (their labels stay on the stack).
inline constexpr Index quad_range = 4096;

//! Over the faces begin .. end, calls quads8(labels) for every eight faces that `is_quad`
//! accepts and one(face) for the others (and for the last few accepted ones).
template <class IsQuad, class Quads8, class One>
void for_quads_in_range(Index begin, Index end, const IsQuad& is_quad, const Quads8& quads8,
                        const One& one)
{
    std::array<Index, std::size_t(quad_range)> quads;
    std::size_t n = 0;
    for (Index f = begin; f < end; ++f)
        if (is_quad(f))
            quads[n++] = f;
        else
            one(f);
    std::size_t i = 0;
    for (; i + lanes8 <= n; i += lanes8)
        quads8(quads.data() + i);
    for (; i < n; ++i)
        one(quads[i]);
}

//! for_quads_in_range over every face, in ranges of quad_range faces spread over the
//! OpenMP threads above `parallel_above` faces.
template <class IsQuad, class Quads8, class One>
void for_quads(Index n_faces, std::int64_t parallel_above, const IsQuad& is_quad,
               const Quads8& quads8, const One& one)
{
    const Index ranges = (n_faces + quad_range - 1) / quad_range;
#pragma omp parallel for schedule(dynamic, 1) if (n_faces > parallel_above)
    for (Index r = 0; r < ranges; ++r)
        for_quads_in_range(r * quad_range, std::min(n_faces, (r + 1) * quad_range), is_quad, quads8,
                           one);
}

} // namespace meshmorph::detail
