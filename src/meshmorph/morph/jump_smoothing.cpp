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

//! The band's linear system: one unknown per free point (row of `band`), the rest Dirichlet:
//! A u = sum over `border` of weight * d(point), A symmetric positive definite.
struct BandSystem
{
    Eigen::SparseMatrix<double> matrix;
    struct Coupling
    {
        Eigen::Index row;
        Index point;
        double weight;
    };
    std::vector<Coupling> border;
};

BandSystem assemble(const PolyMesh& mesh, const CompactList& point_faces,
                    const std::vector<Index>& band, const std::vector<Index>& unknown,
                    const std::vector<double>& wall_distance, double floor)
{
    const Eigen::Index n = Eigen::Index(band.size());
    BandSystem s{Eigen::SparseMatrix<double>(n, n), {}};
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
                s.border.push_back({i, q, w});
        }
        entries.emplace_back(i, i, diagonal);
    }
    s.matrix.setFromTriplets(entries.begin(), entries.end());
    return s;
}

//! The band around the jumps and its factored system (empty band: nothing to do).
struct Band
{
    JumpSmoothing report;
    BandSystem system;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor;
};

//! The band of the prescription (constrained, values) on `mesh`, its system factored.
void make_band(const PolyMesh& mesh, const std::vector<Index>& constrained, const Points& values,
               Band& b)
{
    JumpSmoothing& out = b.report;
    const std::vector<Index> seeds = jump_seeds(mesh, constrained, values, out.width);
    out.jump_constraints = Index(seeds.size());
    if (seeds.empty())
        return;
    const CompactList point_faces = meshmorph::point_faces(mesh);
    const std::vector<double> from_jump = edge_distances(mesh, point_faces, seeds, out.width);
    std::vector<char> is_constrained(std::size_t(mesh.points.rows()), 0);
    for (const Index p : constrained)
        is_constrained[std::size_t(p)] = 1;
    std::vector<Index> unknown(std::size_t(mesh.points.rows()), -1);
    for (Index p = 0; p < mesh.points.rows(); ++p)
        if (from_jump[std::size_t(p)] != unreached && is_constrained[std::size_t(p)] == 0)
        {
            unknown[std::size_t(p)] = Index(out.band.size());
            out.band.push_back(p);
        }
    out.band_points = Index(out.band.size());
    if (out.band.empty())
        return;
    // The diffusivity's distances are capped at the band's depth: the largest distance of a
    // band point from the jump, a length of the mesh and of the band's points alone. (The
    // band's width grows with the motion where the jumps are steep, so a cap at the width
    // would make the smoothing depend on the motion's amplitude, not only on its shape: the
    // smoothing stays linear in the prescription while the band keeps its points.)
    double depth = 0.0;
    for (const Index p : out.band)
        depth = std::max(depth, from_jump[std::size_t(p)]);
    std::vector<double> wall_distance = edge_distances(
        mesh, point_faces, moving_seeds(mesh, seeds, constrained, values), out.width);
    for (double& d : wall_distance)
        d = std::min(d, depth);
    b.system = assemble(mesh, point_faces, out.band, unknown, wall_distance, 1e-3 * depth);
    b.factor.compute(b.system.matrix);
    if (b.factor.info() != Eigen::Success)
        throw SolverError("jump smoothing: the Laplacian of the band around the jumps (" +
                          std::to_string(out.band.size()) +
                          " points) could not be factored; set 'jumpSmoothing no;' in the "
                          "morphDict to morph without it");
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

JumpSmoothing smooth_jumps(const PolyMesh& mesh, const std::vector<Index>& constrained,
                           const Points& values, Points& displacement)
{
    const Stopwatch clock;
    Band b;
    make_band(mesh, constrained, values, b);
    JumpSmoothing& out = b.report;
    if (out.band.empty())
        return out;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(Eigen::Index(out.band.size()), 3);
    for (const BandSystem::Coupling& c : b.system.border)
        rhs.row(c.row) += c.weight * displacement.row(c.point);
    const Eigen::MatrixXd solved = b.factor.solve(rhs);
    out.fitted.resize(Eigen::Index(out.band.size()), 3);
    for (std::size_t i = 0; i < out.band.size(); ++i)
    {
        out.fitted.row(Eigen::Index(i)) = displacement.row(out.band[i]);
        displacement.row(out.band[i]) = solved.row(Eigen::Index(i));
    }
    out.seconds = clock.seconds();
    return out;
}

void smooth_jumps_transpose(const PolyMesh& mesh, const std::vector<Index>& constrained,
                            const Points& values, Points& weights)
{
    Band b;
    make_band(mesh, constrained, values, b);
    const std::vector<Index>& band = b.report.band;
    if (band.empty())
        return;
    // u = A^-1 B d_border, so dJ/dd_border += B^T A^-T dJ/du, with A symmetric.
    Eigen::MatrixXd at_band(Eigen::Index(band.size()), 3);
    for (std::size_t i = 0; i < band.size(); ++i)
        at_band.row(Eigen::Index(i)) = weights.row(band[i]);
    const Eigen::MatrixXd y = b.factor.solve(at_band);
    for (const Index p : band)
        weights.row(p).setZero();
    for (const BandSystem::Coupling& c : b.system.border)
        weights.row(c.point) += c.weight * y.row(c.row);
}

} // namespace meshmorph::morph
