// SPDX-License-Identifier: GPL-3.0-or-later
// Tree-accelerated IDW sums (see the header): median-split trees over sources and queries,
// moments per source node, one interaction list per query block, SIMD kernels over the
// block's points. Built with -fno-math-errno so that sqrt vectorises.
#include "meshmorph/deform/idw_tree.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace meshmorph::detail
{

namespace
{

constexpr Index source_leaf = 16;
constexpr int block_size = 32;

//! A node of a split tree: a contiguous range of the permutation; children at child and
//! child + 1 (-1: leaf).
struct SplitNode
{
    Index begin, end, child;
};

//! How split_tree() cuts a node along the longest side of its bounding box.
enum class SplitRule
{
    //! Sources: in the middle of the side (sliding to the median when that leaves a side
    //! empty, and below depth 96, which bounds the depth for the traversal's stacks). The
    //! cut follows the gaps between parts of a surface, so that a leaf does not span one:
    //! on the motorBike's 57k boundary points the median cut made 10% of the leaves 18 times
    //! wider than their point spacing (the midpoint cut: 11 times), and their direct sums
    //! reach that much further. For the same largest error (6e-4) the median tree needed
    //! theta 0.25 against 0.2 here, and 1.33x the time.
    sources,
    //! Query blocks: at the median, rounded to a multiple of the leaf size so that every
    //! leaf but the last is full (query blocks then fill their SIMD lanes: with halves,
    //! blocks held 21 points on average).
    full_blocks,
};

//! Splits the points (rows of p) recursively until at most leaf_size remain. order becomes
//! the permutation that makes every node a contiguous range. Node 0 is the root; a node's
//! children follow it (breadth first).
std::vector<SplitNode> split_tree(const Points& p, std::vector<Index>& order, Index leaf_size,
                                  SplitRule rule)
{
    constexpr int deepest_midpoint = 96;
    order.resize(static_cast<std::size_t>(p.rows()));
    std::iota(order.begin(), order.end(), Index{0});
    std::vector<SplitNode> nodes{{0, static_cast<Index>(p.rows()), -1}};
    std::vector<int> depth{0};
    for (std::size_t k = 0; k < nodes.size(); ++k)
    {
        const SplitNode node = nodes[k];
        if (node.end - node.begin <= leaf_size)
            continue;
        Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity());
        Vector3 hi = -lo;
        for (Index i = node.begin; i < node.end; ++i)
        {
            lo = lo.cwiseMin(p.row(order[std::size_t(i)]).transpose());
            hi = hi.cwiseMax(p.row(order[std::size_t(i)]).transpose());
        }
        int axis = 0;
        (hi - lo).maxCoeff(&axis);
        const auto first = order.begin() + node.begin, last = order.begin() + node.end;
        Index split = -1;
        if (rule == SplitRule::sources && depth[k] < deepest_midpoint)
        {
            const double cut = 0.5 * (lo[axis] + hi[axis]);
            split = static_cast<Index>(
                std::stable_partition(first, last, [&](Index a) { return p(a, axis) < cut; }) -
                order.begin());
            if (split == node.begin || split == node.end)
                split = -1;
        }
        if (split < 0)
        {
            const Index n = node.end - node.begin;
            const Index half =
                rule == SplitRule::full_blocks ? leaf_size * ((n / leaf_size + 1) / 2) : n / 2;
            std::nth_element(first, first + half, last,
                             [&](Index a, Index b) {
                                 return p(a, axis) < p(b, axis) ||
                                        (p(a, axis) == p(b, axis) && a < b);
                             });
            split = node.begin + half;
        }
        nodes[k].child = static_cast<Index>(nodes.size());
        nodes.push_back({node.begin, split, -1});
        nodes.push_back({split, node.end, -1});
        depth.push_back(depth[k] + 1);
        depth.push_back(depth[k] + 1);
    }
    return nodes;
}

//! r^-a and beta r^-b from 1/r: a fixed (3, 5) fast path and a general one.
struct Weight35
{
    double beta;
    static constexpr double a = 3.0, b = 5.0;
    void operator()(double inv_r, double& pa, double& pb) const
    {
        const double inv_r2 = inv_r * inv_r;
        pa = inv_r2 * inv_r;
        pb = beta * pa * inv_r2;
    }
};
struct WeightGeneral
{
    double beta;
    int ia, ib;
    double a, b;
    void operator()(double inv_r, double& pa, double& pb) const
    {
        pa = 1.0;
        for (int k = 0; k < ia; ++k)
            pa *= inv_r;
        pb = beta * pa;
        for (int k = ia; k < ib; ++k)
            pb *= inv_r;
    }
};

//! out[i] = 1 / sqrt(in[i]) for a whole block. With AVX-512: the 14-bit estimate refined by
//! two Newton steps (56 bits, at least double precision up to a few ulp: these are weights),
//! about three times faster than sqrt and a division; in = 0 gives NaN (a coincident source,
//! whose value replaces the sum). Elsewhere the plain expression, which GCC vectorises.
inline void inverse_sqrt(const double* in, double* out)
{
#if defined(__AVX512F__)
    const __m512d half = _mm512_set1_pd(0.5), three_halves = _mm512_set1_pd(1.5);
    for (int i = 0; i < block_size; i += 8)
    {
        const __m512d x = _mm512_load_pd(in + i);
        __m512d y = _mm512_rsqrt14_pd(x);
        const __m512d hx = _mm512_mul_pd(half, x);
        for (int k = 0; k < 2; ++k)
            y = _mm512_mul_pd(y, _mm512_fnmadd_pd(hx, _mm512_mul_pd(y, y), three_halves));
        _mm512_store_pd(out + i, y);
    }
#else
    for (int i = 0; i < block_size; ++i)
        out[i] = 1.0 / std::sqrt(in[i]);
#endif
}

//! One query block in structure-of-arrays form with its accumulators.
struct Block
{
    int n = 0;
    alignas(64) double x[block_size], y[block_size], z[block_size];
    alignas(64) double nx[block_size], ny[block_size], nz[block_size], den[block_size];
    alignas(64) double hit[block_size];  //!< 1 + source index of a coincident source, or 0
    alignas(64) double lane[block_size]; //!< 1 for the lanes a term applies to, else 0
    alignas(64) double r2[block_size], inv_r[block_size]; //!< scratch of the kernels

    void clear_sums()
    {
        for (int i = 0; i < block_size; ++i)
            nx[i] = ny[i] = nz[i] = den[i] = hit[i] = 0.0;
    }
};

//! Adds the second-order expansion of a far node to the block's points in b.lane.
//! With f the weight, R = x - centroid, r = |R|, delta = s - centroid (sum delta = 0):
//!     sum f(|R - delta|) v ~ f sum v - f'/r R.(sum delta v)
//!                            + 1/2 (f'' - f'/r) R^T (sum delta delta^T v) R / r^2
//!                            + 1/2 f'/r tr(sum delta delta^T v),
//! written in R rather than in R / r so that no per-term normalisation is needed.
template <class W> void add_far(const IdwTree::Node& node, const W& weight, Block& b)
{
    const double count = node.count;
    for (int i = 0; i < block_size; ++i)
    {
        const double rx = b.x[i] - node.cx, ry = b.y[i] - node.cy, rz = b.z[i] - node.cz;
        b.r2[i] = rx * rx + ry * ry + rz * rz;
    }
    inverse_sqrt(b.r2, b.inv_r);
    const auto& first = node.first;
    for (int i = 0; i < block_size; ++i)
    {
        const double rx = b.x[i] - node.cx, ry = b.y[i] - node.cy, rz = b.z[i] - node.cz;
        const double inv_r = b.inv_r[i], inv_r2 = inv_r * inv_r;
        double pa, pb;
        weight(inv_r, pa, pb);
        const double w0 = pa + pb;
        const double d1_r = -(weight.a * pa + weight.b * pb) * inv_r2; // f'/r
        const double d2 =
            (weight.a * (weight.a + 1.0) * pa + weight.b * (weight.b + 1.0) * pb) * inv_r2; // f''
        const double quad = 0.5 * (d2 - d1_r) * inv_r2;
        const double trace = 0.5 * d1_r;
        const double xx = rx * rx, yy = ry * ry, zz = rz * rz;
        const double xy = 2.0 * rx * ry, xz = 2.0 * rx * rz, yz = 2.0 * ry * rz;
        const auto second_order = [&](const double* m, double tr)
        {
            return quad * (xx * m[0] + yy * m[1] + zz * m[2] + xy * m[3] + xz * m[4] + yz * m[5]) +
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

//! Adds one source directly to the block's points in b.lane (and notes coincidences).
template <class W>
void add_source(double sx, double sy, double sz, double vx, double vy, double vz, double tag,
                const W& weight, Block& b)
{
    for (int i = 0; i < block_size; ++i)
    {
        const double dx = b.x[i] - sx, dy = b.y[i] - sy, dz = b.z[i] - sz;
        b.r2[i] = dx * dx + dy * dy + dz * dz;
    }
    inverse_sqrt(b.r2, b.inv_r);
    for (int i = 0; i < block_size; ++i)
    {
        double pa, pb;
        weight(b.inv_r[i], pa, pb);
        const double w = b.lane[i] * (pa + pb);
        b.hit[i] = b.lane[i] > 0.0 && b.r2[i] <= idw_coincident2 ? tag : b.hit[i];
        b.nx[i] += w * vx;
        b.ny[i] += w * vy;
        b.nz[i] += w * vz;
        b.den[i] += w;
    }
}

} // namespace

IdwTree::IdwTree(const Points& sources, const Points& values, const IdwWeight& weight, double theta)
    : weight_(weight), theta_(theta)
{
    std::vector<Index> order;
    const std::vector<SplitNode> split =
        split_tree(sources, order, source_leaf, SplitRule::sources);
    const std::size_t m = order.size();
    for (std::vector<double>* a : {&sx_, &sy_, &sz_, &vx_, &vy_, &vz_})
        a->resize(m);
    for (std::size_t i = 0; i < m; ++i)
    {
        sx_[i] = sources(order[i], 0);
        sy_[i] = sources(order[i], 1);
        sz_[i] = sources(order[i], 2);
        vx_[i] = values(order[i], 0);
        vy_[i] = values(order[i], 1);
        vz_[i] = values(order[i], 2);
    }
    nodes_.resize(split.size());
#pragma omp parallel for schedule(dynamic, 64) if (split.size() > 256)
    for (std::size_t k = 0; k < split.size(); ++k)
    {
        nodes_[k].begin = split[k].begin;
        nodes_[k].end = split[k].end;
        nodes_[k].child = split[k].child;
        compute_moments(nodes_[k]);
    }
    index_probes();
    index_lone_sources();
}

void IdwTree::index_probes()
{
    probes_.resize(nodes_.size());
    for (std::size_t k = 0; k < nodes_.size(); ++k)
    {
        const Node& n = nodes_[k];
        probes_[k] = {n.cx, n.cy, n.cz, n.radius, n.child, n.moments_only};
    }
}

namespace
{

PointKey point_key(double x, double y, double z)
{
    // + 0.0 turns -0 into +0, which compares equal to it.
    return {std::bit_cast<std::uint64_t>(x + 0.0), std::bit_cast<std::uint64_t>(y + 0.0),
            std::bit_cast<std::uint64_t>(z + 0.0)};
}

} // namespace

void IdwTree::index_lone_sources()
{
    // Coincident neighbours are looked for in the source's own leaf only: a leaf is kept
    // whole in a tree written for a -parallel rank, so every rank answers a point as the
    // serial run does. A neighbour in another leaf is possible only within round-off of a
    // split; the point then takes one of the coincident values, as the sum would.
    const double reach2 = 16.0 * idw_coincident2; // generous: a false "yes" only means a sum
    lone_.clear();
    lone_.reserve(sx_.size());
    for (const Node& node : nodes_)
    {
        if (node.child >= 0)
            continue;
        for (Index j = node.begin; j < node.end; ++j)
        {
            const std::size_t sj = static_cast<std::size_t>(j);
            bool lone = true;
            for (Index k = node.begin; k < node.end && lone; ++k)
            {
                const std::size_t sk = static_cast<std::size_t>(k);
                const double dx = sx_[sj] - sx_[sk], dy = sy_[sj] - sy_[sk], dz = sz_[sj] - sz_[sk];
                lone = k == j || dx * dx + dy * dy + dz * dz > reach2;
            }
            if (!lone)
                continue;
            // Equal points in two leaves: neither is looked up (-1: the sum decides).
            const auto [it, inserted] = lone_.emplace(point_key(sx_[sj], sy_[sj], sz_[sj]), j);
            if (!inserted)
                it->second = -1;
        }
    }
}

Index IdwTree::lone_source_at(double x, double y, double z) const
{
    const auto it = lone_.find(point_key(x, y, z));
    return it == lone_.end() ? -1 : it->second;
}

void IdwTree::compute_moments(Node& node) const
{
    const std::size_t b = static_cast<std::size_t>(node.begin),
                      e = static_cast<std::size_t>(node.end);
    node.count = static_cast<double>(e - b);
    double c[3] = {0, 0, 0};
    for (std::size_t j = b; j < e; ++j)
    {
        c[0] += sx_[j];
        c[1] += sy_[j];
        c[2] += sz_[j];
    }
    node.cx = c[0] / node.count;
    node.cy = c[1] / node.count;
    node.cz = c[2] / node.count;
    double r2 = 0.0;
    for (std::size_t j = b; j < e; ++j)
    {
        const double d[3] = {sx_[j] - node.cx, sy_[j] - node.cy, sz_[j] - node.cz};
        const double v[3] = {vx_[j], vy_[j], vz_[j]};
        const double dd[6] = {d[0] * d[0], d[1] * d[1], d[2] * d[2],
                              d[0] * d[1], d[0] * d[2], d[1] * d[2]};
        r2 = std::max(r2, dd[0] + dd[1] + dd[2]);
        for (int k = 0; k < 3; ++k)
        {
            node.sv[k] += v[k];
            for (int a = 0; a < 3; ++a)
                node.first[a][k] += d[a] * v[k];
            for (int q = 0; q < 6; ++q)
                node.second_v[k][q] += dd[q] * v[k];
        }
        for (int q = 0; q < 6; ++q)
            node.second[q] += dd[q];
    }
    node.radius = std::sqrt(r2);
    node.trace[0] = node.second[0] + node.second[1] + node.second[2];
    for (int k = 0; k < 3; ++k)
        node.trace[k + 1] = node.second_v[k][0] + node.second_v[k][1] + node.second_v[k][2];
}

namespace
{

//! A term of a block's sum: a node (far: its expansion; near: a leaf's sources) and the
//! block's lanes it applies to (bit i: point i).
struct Term
{
    Index node;
    std::uint32_t lanes;
};

//! The lanes of the block's points for which `node` is far (radius < theta |x - centroid|,
//! Barnes-Hut's test per point, so that each point's sum depends on the point alone and not
//! on the block, nor on which points a rank holds).
std::uint32_t far_lanes(const IdwTree::Probe& node, double theta, const Block& b,
                        std::uint32_t active)
{
    std::uint32_t far = 0;
    const double limit = node.radius * node.radius;
    for (int i = 0; i < b.n; ++i)
    {
        const double dx = b.x[i] - node.cx, dy = b.y[i] - node.cy, dz = b.z[i] - node.cz;
        const double t2 = theta * theta * (dx * dx + dy * dy + dz * dz);
        if (((active >> i) & 1u) && limit < t2)
            far |= 1u << i;
    }
    return far;
}

//! Far terms and near leaves of a block of n points, in the tree's depth-first order, each
//! with the lanes it applies to. A node far for the whole ball (centre c, radius rho) is
//! far for every point in it; a node that no point sees as far is opened for all. False if
//! a point needs a node written as moments only (a tree written for another region).
bool interaction_lists(const std::vector<IdwTree::Probe>& nodes, double theta, const double c[3],
                       double rho, const Block& b, std::vector<Term>& far, std::vector<Term>& near)
{
    far.clear();
    near.clear();
    const std::uint32_t all = b.n == 32 ? ~0u : (1u << b.n) - 1u;
    // The ball's tests decide for all its points only with a margin far above round-off,
    // so that they never disagree with the test of a point (see far_lanes). Squared, without
    // a square root: a node is far for the whole ball when radius / theta' + rho < |c -
    // centroid|, and may be far for some point unless radius / theta'' - rho >= |c - centroid|.
    const double all_far = 1.0 / ((1.0 - 1e-9) * theta);
    const double some_far = 1.0 / ((1.0 + 1e-9) * theta);
    std::array<Term, 256> stack;
    int top = 0;
    stack[top++] = {0, all};
    while (top > 0)
    {
        const Term t = stack[--top];
        const IdwTree::Probe& node = nodes[std::size_t(t.node)];
        const double dx = c[0] - node.cx, dy = c[1] - node.cy, dz = c[2] - node.cz;
        const double d2 = dx * dx + dy * dy + dz * dz;
        const double whole = node.radius * all_far + rho;
        const double some = node.radius * some_far - rho;
        std::uint32_t far_here = 0;
        if (whole * whole < d2)
            far_here = t.lanes; // the whole ball is far: so is every point
        else if (some <= 0.0 || some * some < d2)
            far_here = far_lanes(node, theta, b, t.lanes); // some point may be far
        if (far_here)
            far.push_back({t.node, far_here});
        const std::uint32_t rest = t.lanes & ~far_here;
        if (!rest)
            continue;
        if (node.moments_only)
            return false;
        if (node.child < 0)
            near.push_back({t.node, rest});
        else
        {
            stack[top++] = {node.child + 1, rest};
            stack[top++] = {node.child, rest};
        }
    }
    return true;
}

} // namespace

namespace
{

//! The distance from p to the box lo..hi (0 inside).
double distance_to_box(const double p[3], const Vector3& lo, const Vector3& hi)
{
    double d2 = 0;
    for (int k = 0; k < 3; ++k)
    {
        const double d = std::max({lo[k] - p[k], 0.0, p[k] - hi[k]});
        d2 += d * d;
    }
    return std::sqrt(d2);
}

} // namespace

void IdwTree::write_essential(FieldWriter& out, const Vector3& lo, const Vector3& hi) const
{
    // Breadth first, so that the two children of a node kept open stay adjacent.
    std::vector<Node> kept{nodes_[0]};
    std::vector<Index> origin{0};
    std::vector<double> sources[6];
    const std::vector<double>* all[6] = {&sx_, &sy_, &sz_, &vx_, &vy_, &vz_};
    for (std::size_t k = 0; k < kept.size(); ++k)
    {
        Node& node = kept[k];
        const double c[3] = {node.cx, node.cy, node.cz};
        // Far for every point of the box (with the margin of interaction_lists).
        const double gap = distance_to_box(c, lo, hi);
        if (gap > 0.0 && node.radius < (1.0 - 1e-9) * theta_ * gap)
        {
            node.moments_only = true;
            node.child = -1;
            node.begin = node.end = 0;
        }
        else if (node.child < 0)
        {
            const Index begin = static_cast<Index>(sources[0].size());
            for (int a = 0; a < 6; ++a)
                sources[a].insert(sources[a].end(), all[a]->begin() + node.begin,
                                  all[a]->begin() + node.end);
            node.end = begin + (node.end - node.begin);
            node.begin = begin;
        }
        else
        {
            const Index child = nodes_[std::size_t(origin[k])].child;
            node.child = static_cast<Index>(kept.size());
            node.begin = node.end = 0; // an inner node's sources are its leaves'
            for (Index c2 : {child, child + 1})
            {
                kept.push_back(nodes_[std::size_t(c2)]);
                origin.push_back(c2);
            }
        }
    }
    out.put_vector(kept);
    for (const std::vector<double>& s : sources)
        out.put_vector(s);
}

IdwTree IdwTree::read_essential(FieldReader& in, const IdwWeight& weight, double theta)
{
    IdwTree tree(weight, theta);
    tree.nodes_ = in.get_vector<Node>();
    for (std::vector<double>* a :
         {&tree.sx_, &tree.sy_, &tree.sz_, &tree.vx_, &tree.vy_, &tree.vz_})
        *a = in.get_vector<double>();
    const Index n_nodes = static_cast<Index>(tree.nodes_.size());
    const Index m = static_cast<Index>(tree.sx_.size());
    if (n_nodes == 0)
        throw IoError("fitted field: an IDW tree without nodes");
    for (std::vector<double>* a : {&tree.sy_, &tree.sz_, &tree.vx_, &tree.vy_, &tree.vz_})
        if (static_cast<Index>(a->size()) != m)
            throw IoError("fitted field: IDW sources of different lengths");
    for (const Node& node : tree.nodes_)
        if (node.begin < 0 || node.end < node.begin || node.end > m ||
            (node.child >= 0 && node.child + 1 >= n_nodes))
            throw IoError("fitted field: an IDW tree node out of range");
    tree.index_probes();
    tree.index_lone_sources();
    return tree;
}

namespace
{

//! The points of query block q into b (unused lanes repeat the first point: harmless work,
//! no branches); their centroid into c. Returns the block's radius about it.
double load_block(const Points& x, const std::vector<Index>& order, const SplitNode& q, Block& b,
                  double c[3])
{
    b.n = static_cast<int>(q.end - q.begin);
    for (int i = 0; i < block_size; ++i)
    {
        const Index p = order[std::size_t(q.begin + (i < b.n ? i : 0))];
        b.x[i] = x(p, 0);
        b.y[i] = x(p, 1);
        b.z[i] = x(p, 2);
    }
    for (int i = 0; i < b.n; ++i)
    {
        c[0] += b.x[i] / b.n;
        c[1] += b.y[i] / b.n;
        c[2] += b.z[i] / b.n;
    }
    double rho2 = 0.0;
    for (int i = 0; i < b.n; ++i)
        rho2 =
            std::max(rho2, (b.x[i] - c[0]) * (b.x[i] - c[0]) + (b.y[i] - c[1]) * (b.y[i] - c[1]) +
                               (b.z[i] - c[2]) * (b.z[i] - c[2]));
    return std::sqrt(rho2);
}

} // namespace

void IdwTree::weighted_mean(const Points& x, Points& out) const
{
    out.resize(x.rows(), 3);
    // A point that is a lone source takes its value: the sum would find the same hit (a
    // source's own leaf is never far for it) and nothing else within the coincidence
    // distance. Only the other points go through the tree.
    const std::int64_t n = static_cast<std::int64_t>(x.rows());
    std::vector<Index> hit(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n > 4096)
    for (std::int64_t i = 0; i < n; ++i)
        hit[std::size_t(i)] = lone_source_at(x(i, 0), x(i, 1), x(i, 2));
    std::vector<Index> rows;
    for (std::int64_t i = 0; i < n; ++i)
    {
        const Index j = hit[std::size_t(i)];
        if (j < 0)
            rows.push_back(Index(i));
        else
            out.row(i) << vx_[std::size_t(j)], vy_[std::size_t(j)], vz_[std::size_t(j)];
    }
    if (rows.size() == std::size_t(n))
    {
        sum_over_tree(x, out);
        return;
    }
    Points xs(static_cast<Eigen::Index>(rows.size()), 3), sums;
    for (std::size_t k = 0; k < rows.size(); ++k)
        xs.row(Eigen::Index(k)) = x.row(rows[k]);
    sum_over_tree(xs, sums);
    for (std::size_t k = 0; k < rows.size(); ++k)
        out.row(rows[k]) = sums.row(Eigen::Index(k));
}

void IdwTree::sum_over_tree(const Points& x, Points& out) const
{
    out.resize(x.rows(), 3);
    if (x.rows() == 0)
        return;
    std::vector<Index> order;
    std::vector<SplitNode> blocks = split_tree(x, order, block_size, SplitRule::full_blocks);
    std::erase_if(blocks, [](const SplitNode& b) { return b.child >= 0; });
    const bool fast = weight_.far_exponent == 3 && weight_.near_exponent == 5;
    const Weight35 w35{weight_.beta};
    const WeightGeneral wg{weight_.beta, weight_.far_exponent, weight_.near_exponent,
                           double(weight_.far_exponent), double(weight_.near_exponent)};
    const std::int64_t n_blocks = static_cast<std::int64_t>(blocks.size());
    std::atomic<bool> outside_region{false};
#pragma omp parallel if (n_blocks > 8)
    {
        std::vector<Term> far, near;
        Block b;
#pragma omp for schedule(dynamic, 16)
        for (std::int64_t k = 0; k < n_blocks; ++k)
        {
            const SplitNode& q = blocks[std::size_t(k)];
            double c[3] = {0, 0, 0};
            const double rho = load_block(x, order, q, b, c);
            // An exception must not leave an OpenMP region: noted, thrown after it.
            if (!interaction_lists(probes_, theta_, c, rho, b, far, near))
            {
                outside_region = true;
                continue;
            }
            b.clear_sums();
            const auto set_lanes = [&](std::uint32_t lanes)
            {
                for (int i = 0; i < block_size; ++i)
                    b.lane[i] = double((lanes >> i) & 1u);
            };
            const auto accumulate = [&](const auto& weight)
            {
                for (const Term& t : far)
                {
                    set_lanes(t.lanes);
                    add_far(nodes_[std::size_t(t.node)], weight, b);
                }
                for (const Term& t : near)
                {
                    set_lanes(t.lanes);
                    const Node& leaf = nodes_[std::size_t(t.node)];
                    for (Index j = leaf.begin; j < leaf.end; ++j)
                        add_source(sx_[j], sy_[j], sz_[j], vx_[j], vy_[j], vz_[j],
                                   static_cast<double>(j + 1), weight, b);
                }
            };
            if (fast)
                accumulate(w35);
            else
                accumulate(wg);
            for (int i = 0; i < b.n; ++i)
            {
                const Index p = order[std::size_t(q.begin + i)];
                if (b.hit[i] > 0.0)
                {
                    const std::size_t j = static_cast<std::size_t>(b.hit[i]) - 1;
                    out.row(p) << vx_[j], vy_[j], vz_[j];
                }
                else
                    out.row(p) << b.nx[i] / b.den[i], b.ny[i] / b.den[i], b.nz[i] / b.den[i];
            }
        }
    }
    if (outside_region)
        throw std::logic_error("IDW: a query outside the region its tree was written for");
}

} // namespace meshmorph::detail
