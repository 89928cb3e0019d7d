// SPDX-License-Identifier: GPL-3.0-or-later
// The jump smoothing's graph and its Laplacian (see the header).
#include "meshmorph/morph/jump_band_graph.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <string>
#include <utility>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/jump_detection.h"
#include "meshmorph/deform/uniform_grid.h"

namespace meshmorph::morph::detail
{

namespace
{

constexpr double unreached = std::numeric_limits<double>::infinity();

//! The points joined to p by an edge of some face, sorted, each once.
std::vector<Index> edge_neighbours(const PolyMesh& mesh, const CompactList& point_faces, Index p)
{
    std::vector<Index> out;
    for (const Index f : point_faces[p])
    {
        const std::span<const Index> loop = mesh.faces[f];
        const std::size_t n = loop.size();
        for (std::size_t k = 0; k < n; ++k)
            if (loop[k] == p)
            {
                out.push_back(loop[(k + 1) % n]);
                out.push_back(loop[(k + n - 1) % n]);
            }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

//! Distances along the edges from `seeds` (0 there), up to `limit` (farther: unreached),
//! through the nodes whose neighbours are listed. Ties leave the queue by node (label)
//! order, so the result depends on nothing else.
std::vector<double> edge_distances(const BandGraph& g, const std::vector<Index>& seeds,
                                   double limit)
{
    std::vector<double> dist(std::size_t(g.size()), unreached);
    using Item = std::pair<double, Index>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (const Index s : seeds)
    {
        dist[std::size_t(s)] = 0.0;
        queue.emplace(0.0, s);
    }
    while (!queue.empty())
    {
        const auto [d, p] = queue.top();
        queue.pop();
        if (d > dist[std::size_t(p)] || g.reached[std::size_t(p)] == 0)
            continue;
        for (const Index q : g.neighbours[std::size_t(p)])
        {
            const double dq = d + (g.x.row(p) - g.x.row(q)).norm();
            if (dq <= limit && dq < dist[std::size_t(q)])
            {
                dist[std::size_t(q)] = dq;
                queue.emplace(dq, q);
            }
        }
    }
    return dist;
}

//! The nodes of the seeds (moving ones only if `moving_only`).
std::vector<Index> seed_nodes(const BandGraph& g, const JumpSeeds& seeds, bool moving_only)
{
    std::vector<Index> out;
    for (std::size_t i = 0; i < seeds.labels.size(); ++i)
        if (!moving_only || seeds.moving[i] != 0)
            if (const Index n = g.node(seeds.labels[i]); n >= 0)
                out.push_back(n);
    return out;
}

void assemble(const BandGraph& g, const std::vector<Index>& unknown,
              const std::vector<double>& wall_distance, double floor, BandSystem& s)
{
    const Eigen::Index n = Eigen::Index(s.band.size());
    Eigen::SparseMatrix<double> matrix(n, n);
    std::vector<Eigen::Triplet<double>> entries;
    for (Eigen::Index i = 0; i < n; ++i)
    {
        const Index p = s.band[std::size_t(i)];
        double diagonal = 0.0;
        for (const Index q : g.neighbours[std::size_t(p)])
        {
            const double length = (g.x.row(p) - g.x.row(q)).norm();
            const double mid =
                0.5 * (wall_distance[std::size_t(p)] + wall_distance[std::size_t(q)]);
            const double w = 1.0 / (std::max(length, floor) * std::max(mid, floor));
            diagonal += w;
            if (const Index j = unknown[std::size_t(q)]; j >= 0)
                entries.emplace_back(i, j, -w);
            else
                s.border.push_back({i, q, w});
        }
        entries.emplace_back(i, i, diagonal);
    }
    matrix.setFromTriplets(entries.begin(), entries.end());
    s.factor.compute(matrix);
}

} // namespace

JumpSeeds jump_seeds(const std::vector<Index>& labels, const Points& positions,
                     const Points& values)
{
    JumpSeeds out;
    const GreedySettings defaults;
    meshmorph::detail::JumpBand band;
    Index count = 0;
    const std::vector<char> jump = meshmorph::detail::jump_constraints(
        positions, values, defaults.jump_slope, defaults.jump_width, band, count);
    if (jump.empty() || count == 0)
        return out;
    out.width = band.width;
    const double largest = values.rowwise().norm().maxCoeff();
    std::vector<Eigen::Index> rows;
    for (std::size_t i = 0; i < labels.size(); ++i)
        if (jump[i] != 0)
        {
            rows.push_back(Eigen::Index(i));
            out.labels.push_back(labels[i]);
            out.moving.push_back(values.row(Eigen::Index(i)).norm() > 1e-6 * largest ? 1 : 0);
        }
    out.positions.resize(Eigen::Index(rows.size()), 3);
    for (std::size_t i = 0; i < rows.size(); ++i)
        out.positions.row(Eigen::Index(i)) = positions.row(rows[i]);
    return out;
}

std::vector<char> within_reach(const Points& x, const Points& seeds, double width, Index stop_above)
{
    std::vector<char> out(std::size_t(x.rows()), 0);
    if (seeds.rows() == 0 || !(width > 0.0))
        return out;
    const meshmorph::detail::UniformGrid grid(seeds, width);
    const double width2 = width * width;
    // Most points are far from every jump: their box test is all they cost.
    const Eigen::RowVector3d low = seeds.colwise().minCoeff().array() - width;
    const Eigen::RowVector3d high = seeds.colwise().maxCoeff().array() + width;
    const std::int64_t n = x.rows();
    std::atomic<Index> reached{0};
#pragma omp parallel for schedule(static) if (n > 4096)
    for (std::int64_t p = 0; p < n; ++p)
    {
        if (stop_above >= 0 && reached.load(std::memory_order_relaxed) > stop_above)
            continue; // past the caller's cap: only "more than that" matters now
        if ((x.row(p).array() >= low.array()).all() && (x.row(p).array() <= high.array()).all() &&
            grid.any_near(x(p, 0), x(p, 1), x(p, 2),
                          [&](std::int64_t s)
                          { return (x.row(p) - seeds.row(s)).squaredNorm() <= width2; }))
        {
            out[std::size_t(p)] = 1;
            reached.fetch_add(1, std::memory_order_relaxed);
        }
    }
    return out;
}

Index count_reached(const std::vector<char>& reached)
{
    return Index(std::count(reached.begin(), reached.end(), char(1)));
}

Index BandGraph::node(Index label) const
{
    const auto at = std::lower_bound(labels.begin(), labels.end(), label);
    return at != labels.end() && *at == label ? Index(at - labels.begin()) : -1;
}

BandGraph local_band_graph(const PolyMesh& mesh, const std::vector<char>& reached,
                           const std::vector<char>& constrained, const Points& d,
                           const std::vector<Index>* label_of)
{
    const auto label_of_point = [&](Index p)
    { return label_of != nullptr ? (*label_of)[std::size_t(p)] : p; };
    const CompactList point_faces = meshmorph::point_faces(mesh);
    std::map<Index, Index> nodes; // label -> mesh point
    std::vector<std::vector<Index>> around(std::size_t(mesh.n_points()));
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (reached[std::size_t(p)] != 0)
        {
            nodes.emplace(label_of_point(p), p);
            around[std::size_t(p)] = edge_neighbours(mesh, point_faces, p);
            for (const Index q : around[std::size_t(p)])
                nodes.emplace(label_of_point(q), q);
        }
    BandGraph g;
    const Eigen::Index n = Eigen::Index(nodes.size());
    g.x.resize(n, 3);
    g.d.resize(n, 3);
    for (const auto& [label, p] : nodes)
    {
        g.x.row(Eigen::Index(g.labels.size())) = mesh.points.row(p);
        g.d.row(Eigen::Index(g.labels.size())) = d.row(p);
        g.labels.push_back(label);
        g.reached.push_back(reached[std::size_t(p)]);
        g.constrained.push_back(constrained[std::size_t(p)]);
        g.points.push_back(p);
    }
    g.neighbours.resize(nodes.size());
    for (std::size_t i = 0; i < g.points.size(); ++i)
    {
        for (const Index q : around[std::size_t(g.points[i])])
            g.neighbours[i].push_back(g.node(label_of_point(q)));
        std::sort(g.neighbours[i].begin(), g.neighbours[i].end());
    }
    return g;
}

void band_system(const BandGraph& g, const JumpSeeds& seeds, BandSystem& s)
{
    if (seeds.labels.empty())
        return;
    const std::vector<double> from_jump =
        edge_distances(g, seed_nodes(g, seeds, false), seeds.width);
    std::vector<Index> unknown(std::size_t(g.size()), -1);
    for (Index p = 0; p < g.size(); ++p)
        if (from_jump[std::size_t(p)] != unreached && g.constrained[std::size_t(p)] == 0 &&
            g.reached[std::size_t(p)] != 0)
        {
            unknown[std::size_t(p)] = Index(s.band.size());
            s.band.push_back(p);
            s.depth = std::max(s.depth, from_jump[std::size_t(p)]);
        }
    if (s.band.empty())
        return;
    // The diffusivity's distances are capped at the band's depth, a length of the mesh and
    // of the band's points alone. (The band's width grows with the motion where the jumps
    // are steep, so a cap at the width would make the smoothing depend on the motion's
    // amplitude, not only on its shape: it stays linear while the band keeps its points.)
    std::vector<double> wall_distance = edge_distances(g, seed_nodes(g, seeds, true), seeds.width);
    for (double& d : wall_distance)
        d = std::min(d, s.depth);
    assemble(g, unknown, wall_distance, 1e-3 * s.depth, s);
    if (s.factor.info() != Eigen::Success)
        throw SolverError("jump smoothing: the Laplacian of the band around the jumps (" +
                          std::to_string(s.band.size()) +
                          " points) could not be factored; set 'jumpSmoothing no;' in the "
                          "morphDict to morph without it");
}

Eigen::MatrixXd solve_band(const BandGraph& g, const BandSystem& s)
{
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(Eigen::Index(s.band.size()), 3);
    for (const BandSystem::Coupling& c : s.border)
        rhs.row(c.row) += c.weight * g.d.row(c.node);
    return s.factor.solve(rhs);
}

void transpose_band(const BandSystem& s, Eigen::MatrixXd& weights)
{
    if (s.band.empty())
        return;
    // u = A^-1 B d_border, so dJ/dd_border += B^T A^-T dJ/du, with A symmetric.
    Eigen::MatrixXd at_band(Eigen::Index(s.band.size()), 3);
    for (std::size_t i = 0; i < s.band.size(); ++i)
        at_band.row(Eigen::Index(i)) = weights.row(s.band[i]);
    const Eigen::MatrixXd y = s.factor.solve(at_band);
    for (const Index p : s.band)
        weights.row(p).setZero();
    for (const BandSystem::Coupling& c : s.border)
        weights.row(c.node) += c.weight * y.row(c.row);
}

} // namespace meshmorph::morph::detail
