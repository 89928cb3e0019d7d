// SPDX-License-Identifier: GPL-3.0-or-later
// Jump smoothing: a Laplacian of the displacement on the band around a jump of the
// prescription, with the fitted field as Dirichlet data.
#include "meshmorph/morph/jump_smoothing.h"

#include <string>

#include "meshmorph/core/stopwatch.h"
#include "meshmorph/morph/jump_band_graph.h"

namespace meshmorph::morph
{

namespace
{

using detail::BandGraph;
using detail::BandSystem;
using detail::JumpSeeds;

//! Rows `rows` of x.
Points rows_of(const Points& x, const std::vector<Index>& rows)
{
    Points out(Eigen::Index(rows.size()), 3);
    for (std::size_t i = 0; i < rows.size(); ++i)
        out.row(Eigen::Index(i)) = x.row(rows[i]);
    return out;
}

//! The graph of the mesh around the seeds (the points `reached`), with the field d (serial:
//! labels are points).
BandGraph serial_graph(const PolyMesh& mesh, const std::vector<char>& reached,
                       const std::vector<Index>& constrained, const Points& d)
{
    std::vector<char> is_constrained(std::size_t(mesh.n_points()), 0);
    for (const Index p : constrained)
        is_constrained[std::size_t(p)] = 1;
    return detail::local_band_graph(mesh, reached, is_constrained, d);
}

//! The band's solved values into `displacement` (the fitted ones kept in `out`).
void apply_band(const BandGraph& g, const BandSystem& s, const Eigen::MatrixXd& solved,
                Points& displacement, JumpSmoothing& out)
{
    out.band_points = Index(s.band.size());
    out.fitted.resize(Eigen::Index(s.band.size()), 3);
    for (std::size_t i = 0; i < s.band.size(); ++i)
    {
        const Index p = g.points[std::size_t(s.band[i])];
        out.band.push_back(p);
        out.fitted.row(Eigen::Index(i)) = displacement.row(p);
        displacement.row(p) = solved.row(Eigen::Index(i));
    }
}

} // namespace

std::string to_string(JumpSmoothingMode mode)
{
    switch (mode)
    {
    case JumpSmoothingMode::off:
        return "no";
    case JumpSmoothingMode::on:
        return "yes";
    case JumpSmoothingMode::automatic:
        break;
    }
    return "auto";
}

JumpSmoothing smooth_jumps(const PolyMesh& mesh, const Points& x_eval,
                           const std::vector<Index>& constrained, const Points& values,
                           Points& displacement, Index max_reach)
{
    const Stopwatch clock;
    JumpSmoothing out;
    const JumpSeeds seeds = detail::jump_seeds(constrained, rows_of(x_eval, constrained), values);
    out.jump_constraints = Index(seeds.labels.size());
    out.width = seeds.width;
    if (seeds.labels.empty())
        return out;
    const std::vector<char> reached =
        detail::within_reach(x_eval, seeds.positions, seeds.width, max_reach);
    if (const Index n = detail::count_reached(reached); n > max_reach)
    {
        out.skipped_reach = n;
        out.seconds = clock.seconds();
        return out;
    }
    const BandGraph g = serial_graph(mesh, reached, constrained, displacement);
    BandSystem s;
    detail::band_system(g, seeds, s);
    if (!s.band.empty())
        apply_band(g, s, detail::solve_band(g, s), displacement, out);
    out.seconds = clock.seconds();
    return out;
}

void smooth_jumps_transpose(const PolyMesh& mesh, const Points& x_eval,
                            const std::vector<Index>& constrained, const Points& values,
                            Points& weights)
{
    const JumpSeeds seeds = detail::jump_seeds(constrained, rows_of(x_eval, constrained), values);
    if (seeds.labels.empty())
        return;
    const std::vector<char> reached =
        detail::within_reach(x_eval, seeds.positions, seeds.width, max_jump_reach_points);
    if (detail::count_reached(reached) > max_jump_reach_points)
        return; // not smoothed (smooth_jumps)
    const BandGraph g = serial_graph(mesh, reached, constrained, weights);
    BandSystem s;
    detail::band_system(g, seeds, s);
    Eigen::MatrixXd w = g.d; // the weights at the graph's nodes
    detail::transpose_band(s, w);
    for (Index n = 0; n < g.size(); ++n)
        weights.row(g.points[std::size_t(n)]) = w.row(n);
}

} // namespace meshmorph::morph
