// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: the SIMD kernels of IdwTree's evaluation. A query block of block_size
//! points (structure of arrays) gains far terms (a node's moment expansion) and near leaves
//! (its sources, summed directly); each term applies to the block's points in a bit mask.
//! Double-precision kernels serve any weight; single-precision ones the default (3, 5).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "meshmorph/core/simd8.h"
#include "meshmorph/deform/idw_node.h"

namespace meshmorph::detail::idw
{

//! Points per query block: the bits of a term's lane mask.
constexpr int block_size = 32;

//! A term of a block's sum: a node (far: its expansion; near: a leaf's sources) and the
//! block's lanes it applies to (bit i: point i).
struct Term
{
    Index node;
    std::uint32_t lanes;
};

//! r^-a and beta r^-b from 1/r: a fixed (3, 5) fast path and a general one.
struct Weight35
{
    double beta;
    static constexpr double a = 3.0, b = 5.0;
    //! T: double, or double8 for eight points at once (the transposed kernels).
    template <class T> void operator()(const T& inv_r, T& pa, T& pb) const
    {
        const T inv_r2 = inv_r * inv_r;
        pa = inv_r2 * inv_r;
        pb = beta * pa * inv_r2;
    }
};
struct WeightGeneral
{
    double beta;
    int ia, ib;
    double a, b;
    template <class T> void operator()(const T& inv_r, T& pa, T& pb) const
    {
        pa = inv_r * 0.0 + 1.0;
        for (int k = 0; k < ia; ++k)
            pa *= inv_r;
        pb = beta * pa;
        for (int k = ia; k < ib; ++k)
            pb *= inv_r;
    }
};

//! The lanes of a SIMD chunk: a block is processed as block_size / chunk chunks, each
//! skipped when a term applies to none of its points.
constexpr int chunk = 8;

//! out[i] = 1 / sqrt(in[i]) for one chunk, by Newton steps (inverse_sqrt8, core/simd8.h:
//! double precision up to a few ulp; these are weights), the same operations in every
//! build; in = 0 gives a huge weight (a coincident source, whose value replaces the sum).
inline void inverse_sqrt(const double* in, double* out)
{
    static_assert(chunk == lanes8);
    store8(out, inverse_sqrt8(load8(in)));
}

//! One query block in structure-of-arrays form with its accumulators.
struct Block
{
    int n = 0;
    alignas(64) double x[block_size], y[block_size], z[block_size];
    alignas(64) double nx[block_size], ny[block_size], nz[block_size], den[block_size];
    alignas(64) double hit[block_size];  //!< 1 + source index of a coincident source, or 0
    alignas(64) double lane[block_size]; //!< 1 for the lanes a term applies to, else 0

    void clear_sums()
    {
        for (int i = 0; i < block_size; ++i)
            nx[i] = ny[i] = nz[i] = den[i] = hit[i] = 0.0;
    }
    //! Sets lane[] from a term's bit mask; returns the mask of the chunks it touches.
    unsigned set_lanes(std::uint32_t lanes)
    {
        unsigned chunks = 0;
        for (int i = 0; i < block_size; ++i)
            lane[i] = double((lanes >> i) & 1u);
        for (int c = 0; c < block_size / chunk; ++c)
            chunks |= ((lanes >> (c * chunk)) & 0xffu) ? 1u << c : 0u;
        return chunks;
    }
};

//! Adds the second-order expansion of a far node to the block's points in b.lane.
//! With f the weight, R = x - centroid, r = |R|, delta = s - centroid (sum delta = 0):
//!     sum f(|R - delta|) v ~ f sum v - f'/r R.(sum delta v)
//!                            + 1/2 (f'' - f'/r) R^T (sum delta delta^T v) R / r^2
//!                            + 1/2 f'/r tr(sum delta delta^T v),
//! written in R rather than in R / r so that no per-term normalisation is needed. A chunk
//! without a lane of the term is skipped: its sums would only gain zeros.
template <class W>
inline void add_far(const IdwNode& node, const W& weight, unsigned chunks, Block& b)
{
    const double count = node.count;
    const auto& first = node.first;
    for (int o = 0; o < block_size; o += chunk)
    {
        if (!((chunks >> (o / chunk)) & 1u))
            continue;
        double r2[chunk], inv_rs[chunk];
        for (int i = o; i < o + chunk; ++i)
        {
            const double rx = b.x[i] - node.cx, ry = b.y[i] - node.cy, rz = b.z[i] - node.cz;
            r2[i - o] = rx * rx + ry * ry + rz * rz;
        }
        inverse_sqrt(r2, inv_rs);
        for (int i = o; i < o + chunk; ++i)
        {
            const double rx = b.x[i] - node.cx, ry = b.y[i] - node.cy, rz = b.z[i] - node.cz;
            const double inv_r = inv_rs[i - o], inv_r2 = inv_r * inv_r;
            double pa, pb;
            weight(inv_r, pa, pb);
            const double w0 = pa + pb;
            const double d1_r = -(weight.a * pa + weight.b * pb) * inv_r2; // f'/r
            const double d2 =
                (weight.a * (weight.a + 1.0) * pa + weight.b * (weight.b + 1.0) * pb) *
                inv_r2; // f''
            const double quad = 0.5 * (d2 - d1_r) * inv_r2;
            const double trace = 0.5 * d1_r;
            const double xx = rx * rx, yy = ry * ry, zz = rz * rz;
            const double xy = 2.0 * rx * ry, xz = 2.0 * rx * rz, yz = 2.0 * ry * rz;
            const auto second_order = [&](const double* m, double tr)
            {
                return quad *
                           (xx * m[0] + yy * m[1] + zz * m[2] + xy * m[3] + xz * m[4] + yz * m[5]) +
                       trace * tr;
            };
            const double on = b.lane[i]; // x + 0 * t == x: lanes off keep their sums exactly
            b.den[i] += on * (count * w0 + second_order(node.second, node.trace[0]));
            b.nx[i] += on * (w0 * node.sv[0] -
                             d1_r * (rx * first[0][0] + ry * first[1][0] + rz * first[2][0]) +
                             second_order(node.second_v[0], node.trace[1]));
            b.ny[i] += on * (w0 * node.sv[1] -
                             d1_r * (rx * first[0][1] + ry * first[1][1] + rz * first[2][1]) +
                             second_order(node.second_v[1], node.trace[2]));
            b.nz[i] += on * (w0 * node.sv[2] -
                             d1_r * (rx * first[0][2] + ry * first[1][2] + rz * first[2][2]) +
                             second_order(node.second_v[2], node.trace[3]));
        }
    }
}

//! Squared distance (normalised units) below which the single-precision kernels take a
//! point to lie at that distance: r >= 1e-8 of the sources' extent keeps beta r^-5 and its
//! sums within float range.
constexpr float single_floor2 = 1e-16f;

//! 16 floats as one GCC vector (one AVX-512 register, or four SSE ones).
using f16 = float __attribute__((vector_size(64)));

//! 1 / sqrt of 16 floats, distances below the floor raised to it: two Newton steps from the
//! bit pattern that halves the exponent (Lomont's constant for float), relative error below
//! 3.5e-2, 1.75e-3, then 4.6e-6 (and rounding). IEEE multiplications and additions only, so
//! the bits are the same on every processor (the rsqrt14 estimate used before has the
//! processor's own bits). A weight's error of 4.6e-6 is far below the far expansions'
//! (~theta^3) and, nearly the same for every weight, mostly cancels in N / D: the
//! motorBike's correction against the direct sum erred by 2.52e-4 of the lift either way.
//! By reference: a 64-byte vector passed by value would change the ABI without AVX-512.
inline void floored_inverse_sqrt16(const f16& r2, f16& out)
{
    using bits16 = unsigned __attribute__((vector_size(64)));
    const f16 x = r2 > single_floor2 ? r2 : single_floor2;
    f16 y = reinterpret_cast<f16>(0x5f375a86u - (reinterpret_cast<bits16>(x) >> 1));
    const f16 h = 0.5f * x;
    for (int step = 0; step < 2; ++step)
        y = y * (1.5f - h * y * y);
    out = y;
}

//! Per-point float accumulators of a block's far terms, added to its double sums once.
struct FarSums
{
    alignas(64) float nx[block_size], ny[block_size], nz[block_size], den[block_size];
    void clear()
    {
        for (int i = 0; i < block_size; ++i)
            nx[i] = ny[i] = nz[i] = den[i] = 0.0f;
    }
    void add_to(Block& b) const
    {
        for (int i = 0; i < block_size; ++i)
        {
            b.nx[i] += double(nx[i]);
            b.ny[i] += double(ny[i]);
            b.nz[i] += double(nz[i]);
            b.den[i] += double(den[i]);
        }
    }
};

//! Adds a far node's expansion for the default weight w = r^-3 + beta r^-5 in single
//! precision to the block's points in `lanes`. Per power p (P = r^-p or beta r^-p,
//! n = R / r) the expansion of add_far() reads
//!     P (S + p (n.F) / r + p (p + 2) / 2 (n^T M n) / r^2 - p / 2 tr(M) / r^2),
//! with S, F, M the node's zeroth, first and second moments of a value. The moment terms
//! take their powers of 1 / r (each then bounded by the node's count and values) before P
//! multiplies them, so that nothing overflows. The offset R = x - centroid is taken in
//! double, so that it is exact to float precision.
inline void add_far_single(const IdwProbe& node, const IdwFarMoments& m, float beta,
                           std::uint32_t lanes, const Block& b, FarSums& f)
{
    constexpr int half = 16;
    for (int o = 0; o < block_size; o += half)
    {
        const std::uint32_t mine = (lanes >> o) & 0xffffu;
        if (!mine)
            continue;
        f16 rx, ry, rz;
        for (int i = 0; i < half; ++i)
        {
            rx[i] = float(b.x[o + i] - node.cx);
            ry[i] = float(b.y[o + i] - node.cy);
            rz[i] = float(b.z[o + i] - node.cz);
        }
        const f16 r2 = rx * rx + ry * ry + rz * rz;
        f16 inv_r;
        floored_inverse_sqrt16(r2, inv_r);
        for (int i = 0; i < half; ++i)
        {
            const float ir = inv_r[i], ir2 = ir * ir;
            const float pa = ir2 * ir, pb = beta * pa * ir2;
            const float on = float((mine >> i) & 1u);
            // The powers' coefficients; the moment terms carry their 1 / r^2 (dimensionless).
            const float w0 = on * (pa + pb), w1 = on * (3.0f * pa + 5.0f * pb),
                        w2 = on * (7.5f * pa + 17.5f * pb), wt = on * (1.5f * pa + 2.5f * pb);
            const float x = rx[i], y = ry[i], z = rz[i];
            const float xx = x * x, yy = y * y, zz = z * z;
            const float xy = 2.0f * x * y, xz = 2.0f * x * z, yz = 2.0f * y * z;
            const auto quadratic = [&](const float* q)
            {
                // (R^T M R / r^2) / r^2: each factor bounded, so that nothing overflows.
                return (xx * q[0] + yy * q[1] + zz * q[2] + xy * q[3] + xz * q[4] + yz * q[5]) *
                       ir2 * ir2;
            };
            const auto linear = [&](int k)
            { return (x * m.first[0][k] + y * m.first[1][k] + z * m.first[2][k]) * ir2; };
            const float t2 = ir2; // tr(M) / r^2
            f.den[o + i] += w0 * m.count + w2 * quadratic(m.second) - wt * (m.trace[0] * t2);
            f.nx[o + i] += w0 * m.sv[0] + w1 * linear(0) + w2 * quadratic(m.second_v[0]) -
                           wt * (m.trace[1] * t2);
            f.ny[o + i] += w0 * m.sv[1] + w1 * linear(1) + w2 * quadratic(m.second_v[1]) -
                           wt * (m.trace[2] * t2);
            f.nz[o + i] += w0 * m.sv[2] + w1 * linear(2) + w2 * quadratic(m.second_v[2]) -
                           wt * (m.trace[3] * t2);
        }
    }
}

//! Sources relative to their leaf's centroid and their values, single precision.
struct SourcesSingle
{
    const float *ox, *oy, *oz, *vx, *vy, *vz;
};

//! The sources begin..end of a near leaf (default weight) in single precision, for the
//! block's points in `lanes`: a point's offset from the leaf's centroid is taken in double,
//! so that its difference from a source is exact to float precision; the leaf's sums are
//! added to the double ones. A point at distance 0 from a source (in float: equal within
//! rounding) notes the hit, whose value replaces the sum.
inline void add_leaf_single(const IdwProbe& leaf, const SourcesSingle& s, Index begin, Index end,
                            float beta, std::uint32_t lanes, Block& b)
{
    // GCC vector types: the sums of a half block stay in registers over the leaf's sources.
    constexpr int half = 16;
    for (int o = 0; o < block_size; o += half)
    {
        const std::uint32_t mine = (lanes >> o) & 0xffffu;
        if (!mine)
            continue;
        f16 px, py, pz, on;
        for (int i = 0; i < half; ++i)
        {
            px[i] = float(b.x[o + i] - leaf.cx);
            py[i] = float(b.y[o + i] - leaf.cy);
            pz[i] = float(b.z[o + i] - leaf.cz);
            on[i] = float((mine >> i) & 1u);
        }
        f16 nx = {}, ny = {}, nz = {}, den = {}, hit = {};
        for (Index j = begin; j < end; ++j)
        {
            const f16 dx = px - s.ox[j], dy = py - s.oy[j], dz = pz - s.oz[j];
            const f16 r2 = dx * dx + dy * dy + dz * dz;
            hit = (on > 0.0f) & (r2 == 0.0f) ? float(j - begin + 1) : hit;
            f16 inv_r;
            floored_inverse_sqrt16(r2, inv_r);
            const f16 ir2 = inv_r * inv_r;
            const f16 pa = ir2 * inv_r;
            const f16 w = on * (pa + beta * pa * ir2);
            nx += w * s.vx[j];
            ny += w * s.vy[j];
            nz += w * s.vz[j];
            den += w;
        }
        for (int i = 0; i < half; ++i)
        {
            b.nx[o + i] += double(nx[i]);
            b.ny[o + i] += double(ny[i]);
            b.nz[o + i] += double(nz[i]);
            b.den[o + i] += double(den[i]);
            b.hit[o + i] = hit[i] > 0.0f ? double(begin) + double(hit[i]) : b.hit[o + i];
        }
    }
}

//! Source arrays in tree order (structure of arrays).
struct SourceArrays
{
    const double *x, *y, *z, *vx, *vy, *vz;
};

//! Adds the sources begin..end of a near leaf directly to the block's points in b.lane (and
//! notes coincidences), chunk by chunk: a chunk's sums stay in registers over the leaf's
//! sources, and each point adds the sources in the same order as one at a time would.
template <class W>
inline void add_leaf(const SourceArrays& s, Index begin, Index end, const W& weight,
                     unsigned chunks, Block& b)
{
    for (int o = 0; o < block_size; o += chunk)
    {
        if (!((chunks >> (o / chunk)) & 1u))
            continue;
        double x[chunk], y[chunk], z[chunk], on[chunk];
        double nx[chunk], ny[chunk], nz[chunk], den[chunk], hit[chunk];
        for (int i = 0; i < chunk; ++i)
        {
            x[i] = b.x[o + i], y[i] = b.y[o + i], z[i] = b.z[o + i], on[i] = b.lane[o + i];
            nx[i] = b.nx[o + i], ny[i] = b.ny[o + i], nz[i] = b.nz[o + i];
            den[i] = b.den[o + i], hit[i] = b.hit[o + i];
        }
        for (Index j = begin; j < end; ++j)
        {
            const double tag = static_cast<double>(j + 1);
            double r2[chunk], inv_r[chunk];
            for (int i = 0; i < chunk; ++i)
            {
                const double dx = x[i] - s.x[j], dy = y[i] - s.y[j], dz = z[i] - s.z[j];
                r2[i] = dx * dx + dy * dy + dz * dz;
            }
            inverse_sqrt(r2, inv_r);
            for (int i = 0; i < chunk; ++i)
            {
                double pa, pb;
                weight(inv_r[i], pa, pb);
                const double w = on[i] * (pa + pb);
                hit[i] = on[i] > 0.0 && r2[i] <= idw_coincident2 ? tag : hit[i];
                nx[i] += w * s.vx[j];
                ny[i] += w * s.vy[j];
                nz[i] += w * s.vz[j];
                den[i] += w;
            }
        }
        for (int i = 0; i < chunk; ++i)
        {
            b.nx[o + i] = nx[i], b.ny[o + i] = ny[i], b.nz[o + i] = nz[i];
            b.den[o + i] = den[i], b.hit[o + i] = hit[i];
        }
    }
}

//! A block's interaction lists and the tree's nodes they name.
struct BlockTerms
{
    const std::vector<Term>& far;
    const std::vector<Term>& near;
    const IdwNode* nodes;
};

//! Every term of a block in double precision (any weight).
template <class W>
inline void add_terms(const BlockTerms& t, const SourceArrays& sources, const W& weight, Block& b)
{
    for (const Term& term : t.far)
        add_far(t.nodes[term.node], weight, b.set_lanes(term.lanes), b);
    for (const Term& term : t.near)
    {
        const IdwNode& leaf = t.nodes[term.node];
        add_leaf(sources, leaf.begin, leaf.end, weight, b.set_lanes(term.lanes), b);
    }
}

//! Every term of a block in single precision (the default weight). The far terms are summed
//! in float and added to the double sums once, so that a point's far terms round the same
//! whichever block it is in.
inline void add_terms_single(const BlockTerms& t, const IdwProbe* probes,
                             const IdwFarMoments* moments, const SourcesSingle& sources, float beta,
                             Block& b, FarSums& fs)
{
    fs.clear();
    for (const Term& term : t.far)
        add_far_single(probes[term.node], moments[term.node], beta, term.lanes, b, fs);
    fs.add_to(b);
    for (const Term& term : t.near)
    {
        const IdwNode& leaf = t.nodes[term.node];
        add_leaf_single(probes[term.node], sources, leaf.begin, leaf.end, beta, term.lanes, b);
    }
}

} // namespace meshmorph::detail::idw
