// SPDX-License-Identifier: GPL-3.0-or-later
// The transpose of IdwTree's weighted mean as a map of the source values: each point's
// weight g / D goes back along the same terms its mean was summed from (a far node's
// expansion, a near leaf's sources, a coincident source), in double precision.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "meshmorph/core/simd8.h"
#include "meshmorph/deform/idw_kernels.h"
#include "meshmorph/deform/idw_split.h"
#include "meshmorph/deform/idw_traversal.h"
#include "meshmorph/deform/idw_tree.h"

namespace meshmorph::detail
{

using namespace idw;

namespace
{

//! A far node's expansion (idw_kernels.h add_far) is, per value component k,
//!     N_k += c . (sv_k, first[0..2][k], second_v[k][0..5], trace[k + 1]),
//! with coefficients c that depend on the point alone. Its transpose collects, per node,
//! sum over points of c (g_k / D): 11 coefficients x 3 components.
constexpr int far_coefficients = 11;
constexpr int node_adjoint_size = far_coefficients * 3;

//! Partial sums over a fixed number of contiguous ranges of query blocks, added in order:
//! the result does not depend on the thread count.
constexpr std::int64_t partial_sums = 8;

//! A query block's weights g_i / D(x_i) per component (0 for a point on a source and for
//! the unused lanes).
struct BlockWeights
{
    alignas(64) double x[block_size] = {}, y[block_size] = {}, z[block_size] = {};
};

//! Lanes of an 8-point chunk of a term's mask as 1.0 / 0.0.
double8 lane_mask(std::uint32_t lanes, int offset)
{
    double8 on;
    for (int i = 0; i < lanes8; ++i)
        on[i] = double((lanes >> (offset + i)) & 1u);
    return on;
}

//! Offsets of a chunk's points from (cx, cy, cz) and their squared distance, at least the
//! single-precision kernels' floor (1e-8 of the sources' extent, as the forward sums take
//! it), and 1 on the lanes off (their terms are multiplied by 0).
void chunk_offsets(const Block& b, int o, double cx, double cy, double cz, const double8& on,
                   double8& rx, double8& ry, double8& rz, double8& r2)
{
    rx = load8(b.x + o) - cx;
    ry = load8(b.y + o) - cy;
    rz = load8(b.z + o) - cz;
    r2 = rx * rx + ry * ry + rz * rz;
    r2 = on > 0.0 ? (r2 > double(single_floor2) ? r2 : double(single_floor2)) : 1.0;
}

double horizontal_sum(const double8& v)
{
    double sum = 0.0;
    for (int i = 0; i < lanes8; ++i)
        sum += v[i];
    return sum;
}

//! Adds, for the block's points in `lanes`, the far node's coefficients times the points'
//! weights to the node's adjoint (node_adjoint_size values), eight points at a time.
template <class W>
void far_transpose(const IdwNode& node, const W& weight, std::uint32_t lanes, const Block& b,
                   const BlockWeights& g, double* adjoint)
{
    double8 sum[far_coefficients][3] = {};
    for (int o = 0; o < block_size; o += lanes8)
    {
        if (!((lanes >> o) & 0xffu))
            continue;
        const double8 on = lane_mask(lanes, o);
        double8 rx, ry, rz, r2;
        chunk_offsets(b, o, node.cx, node.cy, node.cz, on, rx, ry, rz, r2);
        const double8 inv_r = inverse_sqrt8(r2), inv_r2 = inv_r * inv_r;
        double8 pa, pb;
        weight(inv_r, pa, pb);
        // add_far's coefficients; `on` zeroes the lanes the term does not apply to.
        const double8 w0 = on * (pa + pb);
        const double8 d1_r = -on * (weight.a * pa + weight.b * pb) * inv_r2;
        const double8 d2 =
            on * (weight.a * (weight.a + 1.0) * pa + weight.b * (weight.b + 1.0) * pb) * inv_r2;
        const double8 quad = 0.5 * (d2 - d1_r) * inv_r2;
        const double8 c[far_coefficients] = {w0,
                                             -d1_r * rx,
                                             -d1_r * ry,
                                             -d1_r * rz,
                                             quad * rx * rx,
                                             quad * ry * ry,
                                             quad * rz * rz,
                                             2.0 * quad * rx * ry,
                                             2.0 * quad * rx * rz,
                                             2.0 * quad * ry * rz,
                                             0.5 * d1_r};
        const double8 gx = load8(g.x + o), gy = load8(g.y + o), gz = load8(g.z + o);
        for (int t = 0; t < far_coefficients; ++t)
        {
            sum[t][0] += c[t] * gx;
            sum[t][1] += c[t] * gy;
            sum[t][2] += c[t] * gz;
        }
    }
    for (int t = 0; t < far_coefficients; ++t)
        for (int k = 0; k < 3; ++k)
            adjoint[3 * t + k] += horizontal_sum(sum[t][k]);
}

//! Adds, for every source of a near leaf, its weight at the block's points in `lanes` (not
//! on a source) times their weights to the source's adjoint (tree order, row-major).
template <class W>
void leaf_transpose(const IdwTree::Node& leaf, const double* sx, const double* sy, const double* sz,
                    const W& weight, std::uint32_t lanes, const Block& b, const BlockWeights& g,
                    double* adjoint)
{
    std::uint32_t open = 0; // the term's lanes whose point is on no source
    for (int i = 0; i < b.n; ++i)
        if (((lanes >> i) & 1u) && !(b.hit[i] > 0.0))
            open |= 1u << i;
    for (Index j = leaf.begin; j < leaf.end; ++j)
    {
        double8 sum[3] = {};
        for (int o = 0; o < block_size; o += lanes8)
        {
            if (!((open >> o) & 0xffu))
                continue;
            const double8 on = lane_mask(open, o);
            double8 rx, ry, rz, r2;
            chunk_offsets(b, o, sx[j], sy[j], sz[j], on, rx, ry, rz, r2);
            double8 pa, pb;
            weight(inverse_sqrt8(r2), pa, pb);
            const double8 w = on * (pa + pb);
            sum[0] += w * load8(g.x + o);
            sum[1] += w * load8(g.y + o);
            sum[2] += w * load8(g.z + o);
        }
        for (int k = 0; k < 3; ++k)
            adjoint[3 * j + k] += horizontal_sum(sum[k]);
    }
}

//! One query block's share: D(x) and the coincidences from the forward sums (the same
//! kernels as the weighted mean, so the same D and hits), then each far and near term
//! transposed. Flattened, with the block and the float sums its own locals: out of line
//! (the weighted mean is their other caller) or through references (that might alias) GCC
//! compiled the forward kernels 4 times slower than inlined into the weighted mean.
template <class W>
[[gnu::flatten]] void block_transpose(const BlockTerms& terms, const ForwardSums& forward,
                                      const W& weight, const Points& g,
                                      const std::vector<Index>& order, const SplitNode& q,
                                      const Block& loaded, double* node_adjoint, double* adjoint)
{
    Block b = loaded;
    FarSums fs;
    add_block_sums(terms, forward, b, fs);
    BlockWeights w;
    for (int i = 0; i < b.n; ++i)
    {
        const Index p = order[std::size_t(q.begin + i)];
        if (b.hit[i] > 0.0)
        {
            const std::size_t j = static_cast<std::size_t>(b.hit[i]) - 1;
            for (int k = 0; k < 3; ++k)
                adjoint[3 * j + std::size_t(k)] += g(p, k);
            continue;
        }
        w.x[i] = g(p, 0) / b.den[i];
        w.y[i] = g(p, 1) / b.den[i];
        w.z[i] = g(p, 2) / b.den[i];
    }
    for (const Term& t : terms.far)
        far_transpose(terms.nodes[t.node], weight, t.lanes, b, w,
                      node_adjoint + node_adjoint_size * t.node);
    for (const Term& t : terms.near)
        leaf_transpose(terms.nodes[t.node], forward.sources.x, forward.sources.y, forward.sources.z,
                       weight, t.lanes, b, w, adjoint);
}

} // namespace

void IdwTree::weighted_mean_transpose(const Points& x, const Points& g, Points& out) const
{
    if (source_order_.empty())
        throw std::logic_error("IDW transpose: the tree was read for a region, not built from "
                               "every source");
    if (g.rows() != x.rows())
        throw std::logic_error("IDW transpose: weights and points differ in number");
    const std::size_t m = sx_.size();
    std::vector<double> adjoint(3 * m, 0.0);
    // Points on a lone source took its value (weighted_mean): their weight goes to it.
    std::vector<Index> rows;
    rows.reserve(std::size_t(x.rows()));
    for (Eigen::Index i = 0; i < x.rows(); ++i)
    {
        const Index j = lone_source_at(x(i, 0), x(i, 1), x(i, 2));
        if (j < 0)
        {
            rows.push_back(Index(i));
            continue;
        }
        for (int k = 0; k < 3; ++k)
            adjoint[3 * std::size_t(j) + std::size_t(k)] += g(i, k);
    }
    transpose_over_tree(x, g, std::move(rows), adjoint);
    out.setZero(Eigen::Index(m), 3);
    for (std::size_t j = 0; j < m; ++j)
        for (int k = 0; k < 3; ++k)
            out(source_order_[j], k) = adjoint[3 * j + std::size_t(k)];
}

void IdwTree::transpose_over_tree(const Points& x, const Points& g, std::vector<Index> order,
                                  std::vector<double>& adjoint) const
{
    if (order.empty())
        return;
    const std::vector<SplitNode> blocks = query_blocks(x, order, block_size);
    const std::int64_t n_blocks = static_cast<std::int64_t>(blocks.size());
    const std::size_t n_nodes = nodes_.size(), m = sx_.size();
    const SourceArrays sources{sx_.data(), sy_.data(), sz_.data(),
                               ux_.data(), uy_.data(), uz_.data()};
    const bool default_weight = weight_.far_exponent == 3 && weight_.near_exponent == 5;
    const Weight35 w35{weight_.beta};
    const WeightGeneral wg{weight_.beta, weight_.far_exponent, weight_.near_exponent,
                           double(weight_.far_exponent), double(weight_.near_exponent)};
    const SourcesSingle sources_f{ox_.data(),  oy_.data(),  oz_.data(),
                                  fvx_.data(), fvy_.data(), fvz_.data()};
    const ForwardSums forward{sources,
                              probes_.data(),
                              moments_f_.data(),
                              sources_f,
                              float(weight_.beta),
                              default_weight && theta_ > 0.0,
                              w35,
                              wg,
                              default_weight};
    std::vector<std::vector<double>> node_parts(partial_sums), source_parts(partial_sums);
    std::atomic<bool> outside_region{false};
#pragma omp parallel for schedule(dynamic, 1) if (n_blocks > 8)
    for (std::int64_t part = 0; part < partial_sums; ++part)
    {
        std::vector<double>& nodes = node_parts[std::size_t(part)];
        std::vector<double>& own = source_parts[std::size_t(part)];
        nodes.assign(n_nodes * node_adjoint_size, 0.0);
        own.assign(3 * m, 0.0);
        std::vector<Term> far, near;
        Block b;
        for (std::int64_t k = part * n_blocks / partial_sums;
             k < (part + 1) * n_blocks / partial_sums; ++k)
        {
            const SplitNode& q = blocks[std::size_t(k)];
            if (!load_block_terms(x, order, q, probes_, theta_, b, far, near))
            {
                outside_region = true;
                continue;
            }
            const BlockTerms terms{far, near, nodes_.data()};
            if (default_weight)
                block_transpose(terms, forward, w35, g, order, q, b, nodes.data(), own.data());
            else
                block_transpose(terms, forward, wg, g, order, q, b, nodes.data(), own.data());
        }
    }
    if (outside_region)
        throw std::logic_error("IDW: a query outside the region its tree was written for");
    std::vector<double> node_adjoint(n_nodes * node_adjoint_size, 0.0);
    for (std::int64_t part = 0; part < partial_sums; ++part)
    {
        const std::vector<double>& nodes = node_parts[std::size_t(part)];
        const std::vector<double>& own = source_parts[std::size_t(part)];
        for (std::size_t i = 0; i < node_adjoint.size(); ++i)
            node_adjoint[i] += nodes[i];
        for (std::size_t i = 0; i < adjoint.size(); ++i)
            adjoint[i] += own[i];
    }
    push_to_sources(node_adjoint, adjoint);
}

void IdwTree::push_to_sources(const std::vector<double>& node_adjoint,
                              std::vector<double>& adjoint) const
{
    // A source's share of a node's moments (compute_moments): 1, its offset delta from the
    // centroid, delta delta^T (xx yy zz xy xz yz) and |delta|^2, times its value.
    for (std::size_t k = 0; k < nodes_.size(); ++k)
    {
        const double* a = node_adjoint.data() + node_adjoint_size * k;
        if (std::all_of(a, a + node_adjoint_size, [](double v) { return v == 0.0; }))
            continue; // never far for any point
        const Node& node = nodes_[k];
        for (Index j = node.begin; j < node.end; ++j)
        {
            const std::size_t s = std::size_t(j);
            const double d[3] = {sx_[s] - node.cx, sy_[s] - node.cy, sz_[s] - node.cz};
            const double share[far_coefficients] = {1.0,
                                                    d[0],
                                                    d[1],
                                                    d[2],
                                                    d[0] * d[0],
                                                    d[1] * d[1],
                                                    d[2] * d[2],
                                                    d[0] * d[1],
                                                    d[0] * d[2],
                                                    d[1] * d[2],
                                                    d[0] * d[0] + d[1] * d[1] + d[2] * d[2]};
            for (int c = 0; c < 3; ++c)
            {
                double sum = 0.0;
                for (int t = 0; t < far_coefficients; ++t)
                    sum += share[t] * a[3 * t + c];
                adjoint[3 * s + std::size_t(c)] += sum;
            }
        }
    }
}

} // namespace meshmorph::detail
