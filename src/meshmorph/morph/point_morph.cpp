// SPDX-License-Identifier: GPL-3.0-or-later
// One fit of a space deformation to the constraints and its evaluation at every mesh point.
#include "meshmorph/morph/point_morph.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/progress.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/deform/uniform_grid.h"

namespace meshmorph::morph
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
    return c.empty_planes ? c.empty_planes->project(x) : x;
}

void remove_empty_normal(Points& d, const Constraints& c)
{
    if (c.empty_planes)
        c.empty_planes->remove_normal(d);
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

//! The handles a deformation is fitted to.
struct FitHandles
{
    Points positions;
    Points values;
};

//! Row indices of `positions` in lexicographic order (ties by index).
std::vector<Eigen::Index> lexicographic_order(const Points& positions)
{
    std::vector<Eigen::Index> order(static_cast<std::size_t>(positions.rows()));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    std::sort(order.begin(), order.end(),
              [&](Eigen::Index a, Eigen::Index b)
              {
                  for (int k = 0; k < 3; ++k)
                      if (positions(a, k) != positions(b, k))
                          return positions(a, k) < positions(b, k);
                  return a < b;
              });
    return order;
}

//! Handles closer than `same` to each other fitted once: at the position first in
//! lexicographic order, with the mean of their values. In 2D the front and back point of a
//! pair project onto the same position (they differ only by round-off for closed-form
//! motions, by the target's own difference for surfaces and pointDisplacement); meshes with
//! collapsed edges (pitzDaily's merged block corners) add near-duplicate pairs. No solver
//! may see two handles at one position.
FitHandles merge_coincident(const FitHandles& h, double same)
{
    // Cell keys relative to the lower corner stay far below the integer range.
    const Points local = h.positions.rowwise() - h.positions.colwise().minCoeff();
    const detail::UniformGrid grid(local, same);
    std::vector<Eigen::Index> representative(static_cast<std::size_t>(h.positions.rows()), -1);
    Points sums = Points::Zero(h.values.rows(), 3);
    std::vector<int> counts(static_cast<std::size_t>(h.positions.rows()), 0);
    for (const Eigen::Index a : lexicographic_order(h.positions))
    {
        if (representative[std::size_t(a)] >= 0)
            continue;
        grid.for_each_near(local(a, 0), local(a, 1), local(a, 2),
                           [&](Eigen::Index b)
                           {
                               if (representative[std::size_t(b)] < 0 &&
                                   (h.positions.row(a) - h.positions.row(b)).norm() <= same)
                                   representative[std::size_t(b)] = a;
                           });
    }
    for (Eigen::Index i = 0; i < h.positions.rows(); ++i)
    {
        const Eigen::Index r = representative[std::size_t(i)];
        sums.row(r) += h.values.row(i);
        ++counts[std::size_t(r)];
    }
    const Eigen::Index n = std::count_if(counts.begin(), counts.end(), [](int c) { return c > 0; });
    FitHandles out{Points(n, 3), Points(n, 3)};
    for (Eigen::Index i = 0, k = 0; i < h.positions.rows(); ++i)
        if (counts[std::size_t(i)] > 0)
        {
            out.positions.row(k) = h.positions.row(i);
            out.values.row(k++) = sums.row(i) / counts[std::size_t(i)];
        }
    return out;
}

//! The handles to fit: the constrained points at their evaluation positions; in 2D,
//! coincident ones merged.
FitHandles fit_handles(const Points& x_eval, const std::vector<Index>& points,
                       const Points& prescribed, const Constraints& c)
{
    FitHandles h{gather(x_eval, points), prescribed};
    if (!c.empty_planes || points.size() < 2)
        return h;
    const double diag =
        (h.positions.colwise().maxCoeff() - h.positions.colwise().minCoeff()).norm();
    if (!(diag > 0.0)) // every handle at one position
        return merge_coincident(h, std::numeric_limits<double>::max());
    // Projection round-off, far below any mesh spacing.
    return merge_coincident(h, 1e-10 * diag);
}

//! Constrained points and their prescriptions, sorted by point.
struct Prescription
{
    std::vector<Index> points;
    Points values;
};

//! The slip points' prescriptions: the tangential part of a first fit without them (zero if
//! nothing else is prescribed).
Points slip_prescriptions(const Points& x_eval, const Prescription& fixed, const Constraints& c,
                          SpaceDeformation& deformation)
{
    Points slip_values = Points::Zero(static_cast<Eigen::Index>(c.slip_points.size()), 3);
    if (fixed.points.empty())
        return slip_values;
    const FitHandles first = fit_handles(x_eval, fixed.points, fixed.values, c);
    deformation.fit(first.positions, first.values);
    Points d_slip(slip_values.rows(), 3);
    deformation.evaluate(gather(x_eval, c.slip_points), d_slip);
    for (Eigen::Index i = 0; i < d_slip.rows(); ++i)
        slip_values.row(i) =
            (c.slip_projectors[static_cast<std::size_t>(i)] * d_slip.row(i).transpose())
                .transpose();
    remove_empty_normal(slip_values, c);
    return slip_values;
}

//! Both prescriptions in one, sorted by point (the handle order does not matter to the fit,
//! but sorted order keeps runs reproducible).
Prescription merged(const Prescription& a, const std::vector<Index>& b_points,
                    const Points& b_values)
{
    std::vector<std::pair<Index, Vector3>> all;
    all.reserve(a.points.size() + b_points.size());
    for (std::size_t i = 0; i < a.points.size(); ++i)
        all.emplace_back(a.points[i], a.values.row(static_cast<Eigen::Index>(i)).transpose());
    for (std::size_t i = 0; i < b_points.size(); ++i)
        all.emplace_back(b_points[i], b_values.row(static_cast<Eigen::Index>(i)).transpose());
    std::sort(all.begin(), all.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    Prescription out{std::vector<Index>(all.size()),
                     Points(static_cast<Eigen::Index>(all.size()), 3)};
    for (std::size_t i = 0; i < all.size(); ++i)
    {
        out.points[i] = all[i].first;
        out.values.row(static_cast<Eigen::Index>(i)) = all[i].second.transpose();
    }
    return out;
}

//! Fit to the constraints, slip points included (their prescriptions from a first fit).
//! Fitted where the field is evaluated (2D: on the reference empty plane), so an
//! interpolating field meets the constrained points exactly.
Prescription fit_constraints(const Points& x_eval, const Constraints& c,
                             SpaceDeformation& deformation, PointMorph& result)
{
    Prescription p{c.points, c.displacements};
    if (p.points.empty() && c.slip_points.empty())
        throw InvalidInput("nothing to fit: no point has a prescribed displacement (every "
                           "patch is free or slip and there are no handles)");
    if (!c.slip_points.empty())
    {
        p = merged(p, c.slip_points, slip_prescriptions(x_eval, p, c, deformation));
        result.n_slip = static_cast<Index>(c.slip_points.size());
    }
    const FitHandles handles = fit_handles(x_eval, p.points, p.values, c);
    deformation.fit(handles.positions, handles.values);
    return p;
}

//! max over the constrained points of |d - prescribed|.
double max_error(const Points& displacement, const Prescription& p)
{
    double error = 0.0;
    for (std::size_t i = 0; i < p.points.size(); ++i)
        error = std::max(
            error,
            (displacement.row(p.points[i]) - p.values.row(static_cast<Eigen::Index>(i))).norm());
    return error;
}

double max_norm(const Points& values)
{
    return values.rows() == 0 ? 0.0 : values.rowwise().norm().maxCoeff();
}

double diagonal(const Points& x)
{
    return x.rows() > 0 ? (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm() : 1.0;
}

} // namespace

PointMorph morph_points(const PolyMesh& mesh, const Constraints& c, SpaceDeformation& deformation,
                        bool fit, bool snap)
{
    PointMorph result;
    const Points x_eval = evaluation_positions(mesh.points, c);
    const Stopwatch fit_clock;
    const Prescription p = fit ? fit_constraints(x_eval, c, deformation, result)
                               : Prescription{c.points, c.displacements};
    result.report = deformation.report();
    result.fit_seconds = fit_clock.seconds();
    result.n_constraints = static_cast<Index>(p.points.size());

    const Stopwatch eval_clock;
    evaluate_with_progress(deformation, x_eval, result.displacement, "evaluate");
    remove_empty_normal(result.displacement, c);
    result.evaluate_seconds = eval_clock.seconds();

    // The fitted field's residual at the constrained points, then the error of the field
    // actually applied (0 after snapping, up to the 2D projection).
    result.max_prescribed = max_norm(p.values);
    result.max_fit_residual = max_error(result.displacement, p);
    const double scale = std::max(result.max_prescribed, 1e-12 * diagonal(mesh.points));
    result.relative_fit_residual = result.max_fit_residual / scale;
    if (snap && fit)
    {
        for (std::size_t i = 0; i < p.points.size(); ++i)
            result.displacement.row(p.points[i]) = p.values.row(static_cast<Eigen::Index>(i));
        remove_empty_normal(result.displacement, c);
        result.snapped = true;
    }
    result.max_constraint_error = max_error(result.displacement, p);
    result.relative_constraint_error = result.max_constraint_error / scale;
    return result;
}

} // namespace meshmorph::morph
