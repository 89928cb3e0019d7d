// SPDX-License-Identifier: GPL-3.0-or-later
// The jump smoothing of a -parallel morph (see the header).
#include "meshmorph/morph/jump_smoothing_parallel.h"

#include <algorithm>
#include <utility>

#include "meshmorph/core/stopwatch.h"
#include "meshmorph/morph/gathered_by_label.h"
#include "meshmorph/morph/jump_band_graph.h"

namespace meshmorph::morph
{

namespace
{

using detail::BandGraph;
using detail::BandSystem;
using detail::JumpSeeds;

//! A node of a rank's graph as it travels to the master.
struct WireNode
{
    Index label = 0;
    double x[3] = {0, 0, 0};
    double d[3] = {0, 0, 0};
    char reached = 0;
};

//! An edge from a node within reach, by labels.
struct WireEdge
{
    Index from = 0, to = 0;
};

//! A band node's smoothed value, back to a rank.
struct WireValue
{
    Index label = 0;
    double d[3] = {0, 0, 0};
};

//! The seeds' positions and the band's width, from the master to every rank.
std::pair<Points, double> broadcast_seeds(const JumpSeeds& seeds, const parallel::Communicator& c)
{
    std::vector<double> flat{seeds.width};
    for (Eigen::Index i = 0; i < seeds.positions.rows(); ++i)
        for (int k = 0; k < 3; ++k)
            flat.push_back(seeds.positions(i, k));
    flat = c.broadcast_values(flat);
    Points positions((Eigen::Index(flat.size()) - 1) / 3, 3);
    for (Eigen::Index i = 0; i < positions.rows(); ++i)
        for (int k = 0; k < 3; ++k)
            positions(i, k) = flat[std::size_t(1 + 3 * i + k)];
    return {positions, flat[0]};
}

std::vector<WireNode> wire_nodes(const BandGraph& g)
{
    std::vector<WireNode> out(std::size_t(g.size()));
    for (Index n = 0; n < g.size(); ++n)
    {
        WireNode& w = out[std::size_t(n)];
        w.label = g.labels[std::size_t(n)];
        for (int k = 0; k < 3; ++k)
        {
            w.x[k] = g.x(n, k);
            w.d[k] = g.d(n, k);
        }
        w.reached = g.reached[std::size_t(n)];
    }
    return out;
}

std::vector<WireEdge> wire_edges(const BandGraph& g)
{
    std::vector<WireEdge> out;
    for (Index n = 0; n < g.size(); ++n)
        for (const Index q : g.neighbours[std::size_t(n)])
            out.push_back({g.labels[std::size_t(n)], g.labels[std::size_t(q)]});
    return out;
}

//! Every rank's graph as one, on the master: a shared point once (the lowest rank's copy,
//! as the morph's shared points), its edges from every rank.
BandGraph merged_graph(const std::vector<std::vector<WireNode>>& nodes,
                       const std::vector<std::vector<WireEdge>>& edges,
                       const std::vector<Index>& constrained)
{
    const std::vector<WireNode> all = sorted_unique(nodes);
    BandGraph g;
    g.x.resize(Eigen::Index(all.size()), 3);
    g.d.resize(Eigen::Index(all.size()), 3);
    for (std::size_t i = 0; i < all.size(); ++i)
    {
        g.labels.push_back(all[i].label);
        g.x.row(Eigen::Index(i)) << all[i].x[0], all[i].x[1], all[i].x[2];
        g.d.row(Eigen::Index(i)) << all[i].d[0], all[i].d[1], all[i].d[2];
        g.reached.push_back(all[i].reached);
        g.constrained.push_back(
            std::binary_search(constrained.begin(), constrained.end(), all[i].label) ? 1 : 0);
        g.points.push_back(Index(i));
    }
    g.neighbours.resize(all.size());
    for (const std::vector<WireEdge>& rank : edges)
        for (const WireEdge& e : rank)
            g.neighbours[std::size_t(g.node(e.from))].push_back(g.node(e.to));
    for (std::vector<Index>& n : g.neighbours)
    {
        std::sort(n.begin(), n.end());
        n.erase(std::unique(n.begin(), n.end()), n.end());
    }
    return g;
}

//! Per rank, the band's values at the nodes it sent.
std::vector<std::vector<WireValue>> band_values(const BandGraph& g, const BandSystem& s,
                                                const Eigen::MatrixXd& solved,
                                                const std::vector<std::vector<WireNode>>& nodes)
{
    std::vector<Index> row_of(std::size_t(g.size()), -1);
    for (std::size_t i = 0; i < s.band.size(); ++i)
        row_of[std::size_t(s.band[i])] = Index(i);
    std::vector<std::vector<WireValue>> out(nodes.size());
    for (std::size_t r = 0; r < nodes.size(); ++r)
        for (const WireNode& w : nodes[r])
            if (const Index row = row_of[std::size_t(g.node(w.label))]; row >= 0)
            {
                WireValue v;
                v.label = w.label;
                for (int k = 0; k < 3; ++k)
                    v.d[k] = solved(row, k);
                out[r].push_back(v);
            }
    return out;
}

} // namespace

JumpSmoothing smooth_jumps_distributed(const PolyMesh& mesh, const Points& x_eval,
                                       const Decomposition& d,
                                       const std::vector<Index>& constrained,
                                       const Points& positions, const Points& values,
                                       Points& displacement)
{
    const Stopwatch clock;
    const parallel::Communicator& comm = *d.comm;
    JumpSeeds seeds;
    if (comm.master())
        seeds = detail::jump_seeds(constrained, positions, values);
    const auto [seed_positions, width] = broadcast_seeds(seeds, comm);
    JumpSmoothing out;
    out.width = width;
    if (seed_positions.rows() == 0)
        return out;
    // Constrained flags are the master's (the merged prescription, slip points included).
    const std::vector<char> none(std::size_t(mesh.n_points()), 0);
    const std::vector<char> reached =
        detail::within_reach(x_eval, seed_positions, width, max_jump_reach_points);
    // Shared points count on each rank that has them: the cap is a size, not an exact count.
    if (const Index n = Index(comm.sum(std::int64_t(detail::count_reached(reached))));
        n > max_jump_reach_points)
    {
        out.skipped_reach = n;
        out.jump_constraints = Index(seed_positions.rows());
        out.seconds = comm.max(clock.seconds());
        return out;
    }
    const BandGraph local =
        detail::local_band_graph(mesh, reached, none, displacement, &d.global_point);
    const auto nodes = comm.gather_values(wire_nodes(local));
    const auto edges = comm.gather_values(wire_edges(local));
    std::vector<std::vector<WireValue>> answers;
    std::vector<double> counts(2, 0.0);
    if (comm.master())
    {
        const BandGraph g = merged_graph(nodes, edges, constrained);
        BandSystem s;
        detail::band_system(g, seeds, s);
        answers = s.band.empty() ? std::vector<std::vector<WireValue>>(nodes.size())
                                 : band_values(g, s, detail::solve_band(g, s), nodes);
        counts = {double(seeds.labels.size()), double(s.band.size())};
    }
    counts = comm.broadcast_values(counts);
    out.jump_constraints = Index(counts[0]);
    out.band_points = Index(counts[1]);
    const std::vector<WireValue> mine = comm.scatter_values(answers);
    out.fitted.resize(Eigen::Index(mine.size()), 3);
    for (std::size_t i = 0; i < mine.size(); ++i) // ascending labels, as the graph's nodes
    {
        const Index p = local.points[std::size_t(local.node(mine[i].label))];
        out.band.push_back(p);
        out.fitted.row(Eigen::Index(i)) = displacement.row(p);
        displacement.row(p) << mine[i].d[0], mine[i].d[1], mine[i].d[2];
    }
    out.seconds = comm.max(clock.seconds());
    return out;
}

} // namespace meshmorph::morph
