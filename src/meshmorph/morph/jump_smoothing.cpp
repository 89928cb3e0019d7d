// SPDX-License-Identifier: GPL-3.0-or-later
// Jump smoothing: a Laplacian of the displacement on the band around a jump of the
// prescription, with the fitted field as Dirichlet data.
#include "meshmorph/morph/jump_smoothing.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/jump_detection.h"
#include "meshmorph/mesh/point_faces.h"

namespace meshmorph::morph
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

//! Distances along the edges from `seeds` (0 there), up to `limit` (farther: unreached).
//! Ties leave the queue by point label, so the result does not depend on anything else.
std::vector<double> edge_distances(const PolyMesh& mesh, const CompactList& point_faces,
                                   const std::vector<Index>& seeds, double limit)
{
    std::vector<double> dist(static_cast<std::size_t>(mesh.points.rows()), unreached);
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
        if (d > dist[std::size_t(p)])
            continue;
        for (const Index q : edge_neighbours(mesh, point_faces, p))
        {
            const double dq = d + (mesh.points.row(p) - mesh.points.row(q)).norm();
            if (dq <= limit && dq < dist[std::size_t(q)])
            {
                dist[std::size_t(q)] = dq;
                queue.emplace(dq, q);
            }
        }
    }
    return dist;
}

//! The constraints on a jump (deform/jump_detection.h with the greedy RBF's default slope
//! and width, and its reach), as mesh point labels; the band's width in `width`.
std::vector<Index> jump_seeds(const PolyMesh& mesh, const std::vector<Index>& constrained,
                              const Points& values, double& width)
{
    width = 0.0;
    Points x(values.rows(), 3);
    for (std::size_t i = 0; i < constrained.size(); ++i)
        x.row(Eigen::Index(i)) = mesh.points.row(constrained[i]);
    const GreedySettings defaults;
    detail::JumpBand band;
    Index count = 0;
    const std::vector<char> jump =
        detail::jump_constraints(x, values, defaults.jump_slope, defaults.jump_width, band, count);
    if (jump.empty())
        return {};
    std::vector<Index> seeds;
    for (std::size_t i = 0; i < constrained.size(); ++i)
        if (jump[i] != 0)
            seeds.push_back(constrained[i]);
    width = band.width;
    return seeds;
}

//! The seeds that move (|prescription| above 1e-6 of the largest): the diffusivity's walls.
std::vector<Index> moving_seeds(const PolyMesh& mesh, const std::vector<Index>& seeds,
                                const std::vector<Index>& constrained, const Points& values)
{
    std::vector<double> motion(std::size_t(mesh.points.rows()), 0.0);
    for (std::size_t i = 0; i < constrained.size(); ++i)
        motion[std::size_t(constrained[i])] = values.row(Eigen::Index(i)).norm();
    const double largest = values.rowwise().norm().maxCoeff();
    std::vector<Index> out;
    for (const Index s : seeds)
        if (motion[std::size_t(s)] > 1e-6 * largest)
            out.push_back(s);
    return out;
}

//! The band's linear system: one unknown per free point (row of `band`), the rest Dirichlet.
struct BandSystem
{
    Eigen::SparseMatrix<double> matrix;
    Eigen::MatrixXd rhs;
};

BandSystem assemble(const PolyMesh& mesh, const CompactList& point_faces,
                    const std::vector<Index>& band, const std::vector<Index>& unknown,
                    const std::vector<double>& wall_distance, double floor,
                    const Points& displacement)
{
    const Eigen::Index n = Eigen::Index(band.size());
    BandSystem s{Eigen::SparseMatrix<double>(n, n), Eigen::MatrixXd::Zero(n, 3)};
    std::vector<Eigen::Triplet<double>> entries;
    for (Eigen::Index i = 0; i < n; ++i)
    {
        const Index p = band[std::size_t(i)];
        double diagonal = 0.0;
        for (const Index q : edge_neighbours(mesh, point_faces, p))
        {
            const double length = (mesh.points.row(p) - mesh.points.row(q)).norm();
            const double mid =
                0.5 * (wall_distance[std::size_t(p)] + wall_distance[std::size_t(q)]);
            const double w = 1.0 / (std::max(length, floor) * std::max(mid, floor));
            diagonal += w;
            if (const Index j = unknown[std::size_t(q)]; j >= 0)
                entries.emplace_back(i, j, -w);
            else
                s.rhs.row(i) += w * displacement.row(q);
        }
        entries.emplace_back(i, i, diagonal);
    }
    s.matrix.setFromTriplets(entries.begin(), entries.end());
    return s;
}

} // namespace

JumpSmoothing smooth_jumps(const PolyMesh& mesh, const std::vector<Index>& constrained,
                           const Points& values, Points& displacement)
{
    const Stopwatch clock;
    JumpSmoothing out;
    const std::vector<Index> seeds = jump_seeds(mesh, constrained, values, out.width);
    out.jump_constraints = Index(seeds.size());
    if (seeds.empty())
        return out;
    const CompactList point_faces = meshmorph::point_faces(mesh);
    const std::vector<double> from_jump = edge_distances(mesh, point_faces, seeds, out.width);
    std::vector<char> is_constrained(std::size_t(mesh.points.rows()), 0);
    for (const Index p : constrained)
        is_constrained[std::size_t(p)] = 1;
    std::vector<Index> band;
    std::vector<Index> unknown(std::size_t(mesh.points.rows()), -1);
    for (Index p = 0; p < mesh.points.rows(); ++p)
        if (from_jump[std::size_t(p)] != unreached && is_constrained[std::size_t(p)] == 0)
        {
            unknown[std::size_t(p)] = Index(band.size());
            band.push_back(p);
        }
    out.band_points = Index(band.size());
    if (band.empty())
        return out;
    std::vector<double> wall_distance = edge_distances(
        mesh, point_faces, moving_seeds(mesh, seeds, constrained, values), out.width);
    for (double& d : wall_distance)
        d = std::min(d, out.width);
    const BandSystem s =
        assemble(mesh, point_faces, band, unknown, wall_distance, 1e-3 * out.width, displacement);
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(s.matrix);
    if (factor.info() != Eigen::Success)
        throw SolverError("jump smoothing: the Laplacian of the band around the jumps (" +
                          std::to_string(band.size()) +
                          " points) could not be factored; set 'jumpSmoothing no;' in the "
                          "morphDict to morph without it");
    const Eigen::MatrixXd solved = factor.solve(s.rhs);
    for (std::size_t i = 0; i < band.size(); ++i)
        displacement.row(band[i]) = solved.row(Eigen::Index(i));
    out.seconds = clock.seconds();
    return out;
}

} // namespace meshmorph::morph
