// SPDX-License-Identifier: GPL-3.0-or-later
// One fit of a space deformation to the constraints and its evaluation at every mesh point.
#include "meshmorph/app/point_morph.h"

#include <algorithm>
#include <numeric>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/progress.h"
#include "meshmorph/core/stopwatch.h"

namespace meshmorph::app
{

namespace
{

//! Rows `indices` of `x`.
Points gather(const Points& x, const std::vector<Index>& indices)
{
    Points out(static_cast<Eigen::Index>(indices.size()), 3);
    for (std::size_t i = 0; i < indices.size(); ++i)
        out.row(static_cast<Eigen::Index>(i)) = x.row(indices[i]);
    return out;
}

//! Positions at which d is evaluated: in 2D cases the projection onto the reference empty
//! plane, so that both planes get the same displacement.
Points evaluation_positions(const Points& x, const Constraints& c)
{
    if (!c.empty_normal)
        return x;
    const Vector3 n = *c.empty_normal;
    Points out = x;
    const Eigen::VectorXd offset = (x * n).array() - c.empty_offset;
    out -= offset * n.transpose();
    return out;
}

void remove_empty_normal(Points& d, const Constraints& c)
{
    if (!c.empty_normal)
        return;
    const Vector3 n = *c.empty_normal;
    const Eigen::VectorXd normal = d * n;
    d -= normal * n.transpose();
}

//! Evaluate in chunks so long evaluations report progress.
void evaluate_with_progress(const SpaceDeformation& deformation, const Points& x, Points& out,
                            const std::string& task)
{
    out.resize(x.rows(), 3);
    const Eigen::Index chunk = 1 << 16;
    ProgressScope progress(task, x.rows());
    for (Eigen::Index begin = 0; begin < x.rows(); begin += chunk)
    {
        const Eigen::Index n = std::min(chunk, x.rows() - begin);
        deformation.evaluate(x.middleRows(begin, n), out.middleRows(begin, n));
        progress.update(begin + n);
    }
}

//! The handles to fit: the constrained points at their evaluation positions. In 2D the
//! front and back point of each pair project onto the same position; they are fitted once
//! (the first of the pair, averaged with its partner's prescription: they differ only by
//! round-off for closed-form motions, by the target's own difference for surfaces and
//! pointDisplacement), so no solver sees two handles at one position.
struct FitHandles
{
    Points positions;
    Points values;
};

FitHandles fit_handles(const Points& x_eval, const std::vector<Index>& points,
                       const Points& prescribed, const Constraints& c)
{
    FitHandles h{gather(x_eval, points), prescribed};
    if (!c.empty_normal || points.size() < 2)
        return h;
    std::vector<Eigen::Index> order(points.size());
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    const auto less = [&](Eigen::Index a, Eigen::Index b)
    {
        for (int k = 0; k < 3; ++k)
            if (h.positions(a, k) != h.positions(b, k))
                return h.positions(a, k) < h.positions(b, k);
        return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    const double diag =
        (h.positions.colwise().maxCoeff() - h.positions.colwise().minCoeff()).norm();
    const double same = 1e-10 * std::max(diag, 1e-300); // projection round-off, far below spacing
    std::vector<char> keep(points.size(), 1);
    for (std::size_t i = 1; i < order.size(); ++i)
    {
        const Eigen::Index a = order[i - 1], b = order[i];
        if (keep[std::size_t(a)] && (h.positions.row(a) - h.positions.row(b)).norm() <= same)
        {
            h.values.row(a) = 0.5 * (h.values.row(a) + h.values.row(b));
            keep[std::size_t(b)] = 0;
        }
    }
    FitHandles out;
    const Eigen::Index n = std::count(keep.begin(), keep.end(), 1);
    out.positions.resize(n, 3);
    out.values.resize(n, 3);
    for (Eigen::Index i = 0, k = 0; i < h.positions.rows(); ++i)
        if (keep[std::size_t(i)])
        {
            out.positions.row(k) = h.positions.row(i);
            out.values.row(k++) = h.values.row(i);
        }
    return out;
}

} // namespace

PointMorph morph_points(const PolyMesh& mesh, const Constraints& c, SpaceDeformation& deformation,
                        bool fit, bool snap)
{
    PointMorph result;
    const Points& x = mesh.points;
    const Points x_eval = evaluation_positions(x, c);

    std::vector<Index> points = c.points;
    Points prescribed = c.displacements;
    const Stopwatch fit_clock;
    if (fit)
    {
        if (points.empty() && c.slip_points.empty())
            throw InvalidInput("nothing to fit: no point has a prescribed displacement (every "
                               "patch is free or slip and there are no handles)");
        if (!c.slip_points.empty())
        {
            // First fit without the slip points; their prescription is the tangential part
            // of that field (zero if nothing else is prescribed).
            Points slip_values = Points::Zero(static_cast<Eigen::Index>(c.slip_points.size()), 3);
            if (!points.empty())
            {
                const FitHandles first = fit_handles(x_eval, points, prescribed, c);
                deformation.fit(first.positions, first.values);
                Points d_slip(slip_values.rows(), 3);
                deformation.evaluate(gather(x_eval, c.slip_points), d_slip);
                for (Eigen::Index i = 0; i < d_slip.rows(); ++i)
                    slip_values.row(i) =
                        (c.slip_projectors[static_cast<std::size_t>(i)] * d_slip.row(i).transpose())
                            .transpose();
                remove_empty_normal(slip_values, c);
            }
            // Merge, keeping the point order sorted (the handle order does not matter to the
            // fit, but sorted order keeps runs reproducible).
            std::vector<std::pair<Index, Vector3>> all;
            all.reserve(points.size() + c.slip_points.size());
            for (std::size_t i = 0; i < points.size(); ++i)
                all.emplace_back(points[i],
                                 prescribed.row(static_cast<Eigen::Index>(i)).transpose());
            for (std::size_t i = 0; i < c.slip_points.size(); ++i)
                all.emplace_back(c.slip_points[i],
                                 slip_values.row(static_cast<Eigen::Index>(i)).transpose());
            std::sort(all.begin(), all.end(),
                      [](const auto& a, const auto& b) { return a.first < b.first; });
            points.resize(all.size());
            prescribed.resize(static_cast<Eigen::Index>(all.size()), 3);
            for (std::size_t i = 0; i < all.size(); ++i)
            {
                points[i] = all[i].first;
                prescribed.row(static_cast<Eigen::Index>(i)) = all[i].second.transpose();
            }
            result.n_slip = static_cast<Index>(c.slip_points.size());
        }
        // Fitted where the field is evaluated (2D: on the reference empty plane), so an
        // interpolating field meets the constrained points exactly.
        const FitHandles handles = fit_handles(x_eval, points, prescribed, c);
        deformation.fit(handles.positions, handles.values);
    }
    result.report = deformation.report();
    result.fit_seconds = fit_clock.seconds();
    result.n_constraints = static_cast<Index>(points.size());

    const Stopwatch eval_clock;
    evaluate_with_progress(deformation, x_eval, result.displacement, "evaluate");
    remove_empty_normal(result.displacement, c);
    result.evaluate_seconds = eval_clock.seconds();

    // Residual of the fitted field at the constrained points.
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        const Eigen::Index r = static_cast<Eigen::Index>(i);
        result.max_prescribed = std::max(result.max_prescribed, prescribed.row(r).norm());
        result.max_fit_residual =
            std::max(result.max_fit_residual,
                     (result.displacement.row(points[i]) - prescribed.row(r)).norm());
    }
    double diag = 1.0;
    if (mesh.n_points() > 0)
        diag = (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
    const double scale = std::max(result.max_prescribed, 1e-12 * diag);
    result.relative_fit_residual = result.max_fit_residual / scale;
    if (snap && fit)
    {
        for (std::size_t i = 0; i < points.size(); ++i)
            result.displacement.row(points[i]) = prescribed.row(static_cast<Eigen::Index>(i));
        remove_empty_normal(result.displacement, c);
        result.snapped = true;
    }
    // The error of the field actually applied (0 after snapping, up to the 2D projection).
    for (std::size_t i = 0; i < points.size(); ++i)
        result.max_constraint_error =
            std::max(result.max_constraint_error, (result.displacement.row(points[i]) -
                                                   prescribed.row(static_cast<Eigen::Index>(i)))
                                                      .norm());
    result.relative_constraint_error = result.max_constraint_error / scale;
    return result;
}

} // namespace meshmorph::app
