// SPDX-License-Identifier: GPL-3.0-or-later
// Tree-accelerated IDW sums (see the header): the source tree with moments per node, one
// interaction list per query block, the kernels of idw_kernels.h over the block's points.
// Built with -fno-math-errno so that sqrt vectorises.
#include "meshmorph/deform/idw_tree.h"

#include "meshmorph/deform/idw_kernels.h"
#include "meshmorph/deform/idw_split.h"
#include "meshmorph/deform/idw_traversal.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace meshmorph::detail
{

using namespace idw;

namespace
{

constexpr Index source_leaf = 16;

//! The radius the opening test compares with theta times the distance.
double opening_radius(const IdwNode& node)
{
    return node.quiet ? node.radius / quiet_theta_factor : node.radius;
}

} // namespace

IdwTree::IdwTree(const Points& sources, const Points& values, const IdwWeight& weight, double theta,
                 const std::vector<char>& quiet)
    : weight_(weight), theta_(theta)
{
    std::vector<Index> order;
    // The quiet sources apart from the others below the root: a node mixing the two is not
    // quiet, so every ancestor of a loud source was expanded at theta (mark_quiet_nodes).
    const std::vector<SplitNode> split = split_sources(sources, order, source_leaf, quiet);
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
    for (int k = 0; k < 3; ++k)
        mid_[k] = 0.5 * (values.col(k).minCoeff() + values.col(k).maxCoeff());
    source_order_ = order;
    shift_values();
    nodes_.resize(split.size());
#pragma omp parallel for schedule(dynamic, 64) if (split.size() > 256)
    for (std::size_t k = 0; k < split.size(); ++k)
    {
        nodes_[k].begin = split[k].begin;
        nodes_[k].end = split[k].end;
        nodes_[k].child = split[k].child;
        compute_moments(nodes_[k]);
    }
    mark_quiet_nodes(quiet, order);
    index_probes();
    index_single_sources();
    index_lone_sources();
}

void IdwTree::mark_quiet_nodes(const std::vector<char>& quiet, const std::vector<Index>& order)
{
    if (quiet.empty())
        return; // IdwDeformation::fit checked the size otherwise
    std::vector<char> in_tree_order(order.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        in_tree_order[i] = quiet[std::size_t(order[i])];
    for (Node& node : nodes_)
        node.quiet = std::all_of(in_tree_order.begin() + node.begin,
                                 in_tree_order.begin() + node.end, [](char q) { return q != 0; });
}

void IdwTree::shift_values()
{
    const std::size_t m = vx_.size();
    for (std::vector<double>* a : {&ux_, &uy_, &uz_})
        a->resize(m);
    for (std::size_t j = 0; j < m; ++j)
    {
        ux_[j] = vx_[j] - mid_[0];
        uy_[j] = vy_[j] - mid_[1];
        uz_[j] = vz_[j] - mid_[2];
    }
}

void IdwTree::index_probes()
{
    probes_.resize(nodes_.size());
    moments_f_.resize(nodes_.size());
    for (std::size_t k = 0; k < nodes_.size(); ++k)
    {
        const Node& n = nodes_[k];
        probes_[k] = {n.cx, n.cy, n.cz, opening_radius(n), n.child, n.moments_only};
        FarMoments& m = moments_f_[k];
        m.count = float(n.count);
        for (int a = 0; a < 3; ++a)
        {
            m.sv[a] = float(n.sv[a]);
            for (int k2 = 0; k2 < 3; ++k2)
                m.first[a][k2] = float(n.first[a][k2]);
            for (int q = 0; q < 6; ++q)
                m.second_v[a][q] = float(n.second_v[a][q]);
        }
        for (int q = 0; q < 6; ++q)
            m.second[q] = float(n.second[q]);
        for (int q = 0; q < 4; ++q)
            m.trace[q] = float(n.trace[q]);
    }
}

void IdwTree::index_single_sources()
{
    const std::size_t n_sources = sx_.size();
    for (std::vector<float>* a : {&ox_, &oy_, &oz_, &fvx_, &fvy_, &fvz_})
        a->resize(n_sources);
    for (const Node& n : nodes_)
    {
        if (n.child >= 0)
            continue; // an inner node's sources are its leaves'
        for (std::size_t j = std::size_t(n.begin); j < std::size_t(n.end); ++j)
        {
            ox_[j] = float(sx_[j] - n.cx);
            oy_[j] = float(sy_[j] - n.cy);
            oz_[j] = float(sz_[j] - n.cz);
            fvx_[j] = float(ux_[j]);
            fvy_[j] = float(uy_[j]);
            fvz_[j] = float(uz_[j]);
        }
    }
}

void IdwTree::index_lone_sources()
{
    // Coincident neighbours are looked for in the source's own leaf only: a leaf is kept
    // whole in a tree written for a -parallel rank, so every rank answers a point as the
    // serial run does. A neighbour in another leaf is possible only within round-off of a
    // split; the point then takes one of the coincident values, as the sum would.
    const double reach2 = 16.0 * idw_coincident2; // generous: a false "yes" only means a sum
    lone_ = ExactPointIndex(sx_.size());
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
            lone_.insert(sx_[sj], sy_[sj], sz_[sj], j);
        }
    }
}

Index IdwTree::lone_source_at(double x, double y, double z) const
{
    return lone_.find(x, y, z);
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
        const double v[3] = {ux_[j], uy_[j], uz_[j]};
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

//! The lanes of the block's points for which `node` is far (radius < theta |x - centroid|,
//! Barnes-Hut's test per point, so that each point's sum depends on the point alone and not
//! on the block, nor on which points a rank holds).
std::uint32_t far_lanes(const IdwTree::Probe& node, double theta, const Block& b,
                        std::uint32_t active)
{
    const double limit = node.radius * node.radius;
    std::uint32_t far = 0;
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
bool interaction_lists(const std::vector<IdwProbe>& nodes, double theta, const double c[3],
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
        if (gap > 0.0 && opening_radius(node) < (1.0 - 1e-9) * theta_ * gap)
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
    out.put_vector(std::vector<double>(mid_, mid_ + 3));
}

IdwTree IdwTree::read_essential(FieldReader& in, const IdwWeight& weight, double theta)
{
    IdwTree tree(weight, theta);
    tree.nodes_ = in.get_vector<Node>();
    for (std::vector<double>* a :
         {&tree.sx_, &tree.sy_, &tree.sz_, &tree.vx_, &tree.vy_, &tree.vz_})
        *a = in.get_vector<double>();
    const std::vector<double> mid = in.get_vector<double>();
    if (mid.size() != 3)
        throw IoError("fitted field: an IDW tree without its values' midrange");
    std::copy(mid.begin(), mid.end(), tree.mid_);
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
    tree.shift_values();
    tree.index_probes();
    tree.index_single_sources();
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

bool idw::load_block_terms(const Points& x, const std::vector<Index>& order, const SplitNode& q,
                           const std::vector<IdwProbe>& nodes, double theta, Block& b,
                           std::vector<Term>& far, std::vector<Term>& near)
{
    double c[3] = {0, 0, 0};
    const double rho = load_block(x, order, q, b, c);
    return interaction_lists(nodes, theta, c, rho, b, far, near);
}

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
    rows.reserve(std::size_t(n));
    for (std::int64_t i = 0; i < n; ++i)
    {
        const Index j = hit[std::size_t(i)];
        if (j < 0)
            rows.push_back(Index(i));
        else
            out.row(i) << vx_[std::size_t(j)], vy_[std::size_t(j)], vz_[std::size_t(j)];
    }
    sum_over_tree(x, std::move(rows), out);
}

void IdwTree::sum_over_tree(const Points& x, std::vector<Index> order, Points& out) const
{
    if (order.empty())
        return;
    const std::vector<SplitNode> blocks = query_blocks(x, order, block_size);
    const bool default_weight = weight_.far_exponent == 3 && weight_.near_exponent == 5;
    // The single-precision kernels exist for the default weight; theta = 0, the exact
    // reference of the tests and benchmarks, sums in double.
    const bool single = default_weight && theta_ > 0.0;
    const Weight35 w35{weight_.beta};
    const WeightGeneral wg{weight_.beta, weight_.far_exponent, weight_.near_exponent,
                           double(weight_.far_exponent), double(weight_.near_exponent)};
    const std::int64_t n_blocks = static_cast<std::int64_t>(blocks.size());
    const SourceArrays sources{sx_.data(), sy_.data(), sz_.data(),
                               ux_.data(), uy_.data(), uz_.data()};
    const SourcesSingle sources_f{ox_.data(),  oy_.data(),  oz_.data(),
                                  fvx_.data(), fvy_.data(), fvz_.data()};
    std::atomic<bool> outside_region{false};
#pragma omp parallel if (n_blocks > 8)
    {
        std::vector<Term> far, near;
        Block b;
        FarSums fs;
#pragma omp for schedule(dynamic, 16)
        for (std::int64_t k = 0; k < n_blocks; ++k)
        {
            const SplitNode& q = blocks[std::size_t(k)];
            // An exception must not leave an OpenMP region: noted, thrown after it.
            if (!load_block_terms(x, order, q, probes_, theta_, b, far, near))
            {
                outside_region = true;
                continue;
            }
            b.clear_sums();
            const BlockTerms terms{far, near, nodes_.data()};
            if (single)
                add_terms_single(terms, probes_.data(), moments_f_.data(), sources_f,
                                 float(weight_.beta), b, fs);
            else if (default_weight)
                add_terms(terms, sources, w35, b);
            else
                add_terms(terms, sources, wg, b);
            for (int i = 0; i < b.n; ++i)
            {
                const Index p = order[std::size_t(q.begin + i)];
                if (b.hit[i] > 0.0)
                {
                    const std::size_t j = static_cast<std::size_t>(b.hit[i]) - 1;
                    out.row(p) << vx_[j], vy_[j], vz_[j];
                }
                else
                    out.row(p) << mid_[0] + b.nx[i] / b.den[i], mid_[1] + b.ny[i] / b.den[i],
                        mid_[2] + b.nz[i] / b.den[i];
            }
        }
    }
    if (outside_region)
        throw std::logic_error("IDW: a query outside the region its tree was written for");
}

} // namespace meshmorph::detail
