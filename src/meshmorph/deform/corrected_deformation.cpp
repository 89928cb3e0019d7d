// SPDX-License-Identifier: GPL-3.0-or-later
// Global deformation plus the IDW interpolant of its residual.
#include "meshmorph/deform/corrected_deformation.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph
{

void detail::limit_to_ball(Eigen::Ref<Points> d, double radius)
{
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < d.rows(); ++i)
    {
        const double n = d.row(i).norm();
        if (n > radius)
            d.row(i) *= radius / n;
    }
}

namespace
{

//! The handles whose residuals the correction's tree may treat as quiet (detail::IdwTree):
//! all but those the global part left out (a greedy RBF's jumps, whose residuals are large
//! and few). None when the global part fits the others to worse than 1/32 of the largest
//! prescription: a quiet node's error per unit of value is ~11 times that of theta (4th
//! power of 1.75), so only residuals within 1/32 keep the error theta allows.
std::vector<char> quiet_handles(const SpaceDeformation& global, Index handles, double largest)
{
    if (!(global.report().max_fitted_residual <= largest / 32.0))
        return {};
    std::vector<char> quiet(std::size_t(handles), 1);
    const std::vector<char>* left_out = global.handles_left_out();
    if (left_out == nullptr)
        return quiet;
    if (left_out->size() != quiet.size())
        return {}; // not of these handles: no node is quiet (theta everywhere)
    for (std::size_t i = 0; i < quiet.size(); ++i)
        quiet[i] = !(*left_out)[i];
    return quiet;
}

} // namespace

CorrectedDeformation::CorrectedDeformation(std::unique_ptr<SpaceDeformation> global,
                                           const IdwSettings& correction, bool limit)
    : global_(std::move(global)), correction_(correction), limit_(limit)
{
    if (!global_)
        throw InvalidInput("CorrectedDeformation: no global deformation given");
}

CorrectedDeformation::~CorrectedDeformation() = default;

void CorrectedDeformation::fit(const Eigen::Ref<const Points>& handles,
                               const Eigen::Ref<const Points>& displacements)
{
    try
    {
        global_->fit(handles, displacements);
    }
    catch (const SolverError& e)
    {
        // A direct RBF on constraints that nearly coincide (the layers of a wall-resolved
        // mesh where an inlet meets a wall: spacings of 1e-6 of the domain) is numerically
        // singular, or so ill-conditioned that it misses its handles (when its settings ask
        // for the error: RbfSettings::ill_conditioning_is_error). The greedy RBF chooses centres
        // that stay apart, and the correction keeps the field exact at every constraint either way.
        // This is the designed path for such meshes (the adjoint tutorials' sbend), so it is a log
        // line, not a warning: the result is as exact, and there is nothing for the user to change.
        const auto* direct = dynamic_cast<const RbfDeformation*>(global_.get());
        if (direct == nullptr)
            throw;
        // Said once per process: a design set-up fits every variable, a morph every step,
        // and the same lines for each would bury the log (a 2D case takes this path always).
        static std::atomic<bool> told{false};
        if (!told.exchange(true))
            log::info() << e.what()
                        << "; using the greedy RBF instead, whose centres stay apart (the IDW "
                           "correction keeps the field exact; rbf { greedy { } } chooses it "
                           "from the start). Said once: later fits of this run take the same "
                           "path without a word";
        GreedySettings greedy;
        greedy.rbf = direct->settings();
        global_ = std::make_unique<GreedyRbfDeformation>(greedy);
        global_->fit(handles, displacements);
    }
    handles_ = handles;
    const double largest = displacements.rowwise().norm().maxCoeff();
    quiet_ = quiet_handles(*global_, handles.rows(), largest);
    fit_correction(displacements);
}

void CorrectedDeformation::refit(const Eigen::Ref<const Points>& displacements)
{
    if (!is_fitted())
        throw InvalidInput("CorrectedDeformation: refit before fit");
    global_->refit(displacements);
    fit_correction(displacements);
}

void CorrectedDeformation::fit_correction(const Eigen::Ref<const Points>& displacements)
{
    const Points& handles = handles_;
    Points residual(handles.rows(), 3);
    handle_rows_ = {};
    global_at_handles_.resize(0, 3);
    if (const Points* at = global_->values_at_handles(); at && at->rows() == handles.rows())
    {
        residual = displacements - *at;
        handle_rows_ = detail::ExactPointIndex(handles);
        global_at_handles_ = *at;
    }
    else
    {
        global_->evaluate(handles, residual);
        residual = displacements - residual;
    }
    const double largest = displacements.rowwise().norm().maxCoeff(&largest_row_);
    correction_.fit(handles, residual, quiet_);
    largest_direction_ =
        largest > 0.0 ? Vector3(displacements.row(largest_row_) / largest) : Vector3::Zero();
    report_ = global_->report();
    report_.method += "+idw";
    report_.max_displacement = largest;
    report_.max_residual = residual.rowwise().norm().maxCoeff();
    if (report_.jump_constraints == 0)
        report_.max_fitted_residual = report_.max_residual;
    report_.rms_residual = std::sqrt(residual.rowwise().squaredNorm().mean());
}

void CorrectedDeformation::write_field(FieldWriter& out) const
{
    if (limit_)
    {
        out.put(FieldKind::limited);
        out.put(report_.max_displacement);
    }
    out.put(FieldKind::sum);
    global_->write_field(out);
    correction_.write_field(out);
}

void CorrectedDeformation::evaluate_global(const Eigen::Ref<const Points>& points,
                                           Eigen::Ref<Points> out) const
{
    if (handle_rows_.empty())
    {
        global_->evaluate(points, out);
        return;
    }
    // A morph evaluates the field at its constraints too (on the motorBike 57k of 406k
    // points, each a sum over every centre): those take the fit's values. The other points
    // go through the global part in pieces, so that the gathered copies stay small (fresh
    // pages cost more than the copies on a virtual machine); the gathers and scatters run
    // on every thread, and pieces of 2^16 points keep the evaluation's tails short (one per
    // piece).
    const std::vector<Index> at_handle = handle_rows_.find_rows(points);
    std::vector<Eigen::Index> rows;
    rows.reserve(std::size_t(points.rows()));
    for (Eigen::Index i = 0; i < points.rows(); ++i)
        if (at_handle[std::size_t(i)] < 0)
            rows.push_back(i);
#pragma omp parallel for schedule(static) if (points.rows() > 4096)
    for (std::int64_t i = 0; i < std::int64_t(points.rows()); ++i)
        if (const Index j = at_handle[std::size_t(i)]; j >= 0)
            out.row(i) = global_at_handles_.row(j);
    const std::int64_t piece = std::min<std::int64_t>(std::int64_t(rows.size()), 1 << 16);
    Points x(piece, 3), g(piece, 3);
    for (std::int64_t begin = 0; begin < std::int64_t(rows.size()); begin += piece)
    {
        const std::int64_t n = std::min<std::int64_t>(piece, std::int64_t(rows.size()) - begin);
#pragma omp parallel for schedule(static) if (n > 4096)
        for (std::int64_t k = 0; k < n; ++k)
            x.row(k) = points.row(rows[std::size_t(begin + k)]);
        global_->evaluate(x.topRows(n), g.topRows(n));
#pragma omp parallel for schedule(static) if (n > 4096)
        for (std::int64_t k = 0; k < n; ++k)
            out.row(rows[std::size_t(begin + k)]) = g.row(k);
    }
}

void CorrectedDeformation::evaluate(const Eigen::Ref<const Points>& points,
                                    Eigen::Ref<Points> out) const
{
    // The parts check their points; the rows of out first, as the shortcut writes them.
    detail::check_output_rows(points, out, "corrected deformation");
    evaluate_unlimited(points, out);
    if (limit_)
        detail::limit_to_ball(out, report_.max_displacement);
}

void CorrectedDeformation::evaluate_unlimited(const Eigen::Ref<const Points>& points,
                                              Eigen::Ref<Points> out) const
{
    evaluate_global(points, out);
    Points c(points.rows(), 3);
    correction_.evaluate(points, c);
#pragma omp parallel for schedule(static) if (points.rows() > 4096)
    for (std::int64_t i = 0; i < std::int64_t(points.rows()); ++i)
        out.row(i) += c.row(i);
}

Points CorrectedDeformation::transpose(const Eigen::Ref<const Points>& points,
                                       const Eigen::Ref<const Points>& weights) const
{
    detail::check_transpose_arguments(is_fitted(), points, weights, "corrected deformation");
    Points g = weights;
    double toward_largest = 0.0;
    if (limit_)
        toward_largest = limit_transpose(points, g);
    // d = g(x) + c(x), c the IDW interpolant of the residual r = H - g(handles).
    const Points residual_adjoint = correction_.transpose(points, g);
    Points adjoint = residual_adjoint + global_->transpose(points, g);
    adjoint -= global_->transpose(handles_, residual_adjoint);
    adjoint.row(largest_row_) += toward_largest * largest_direction_.transpose();
    return adjoint;
}

double CorrectedDeformation::limit_transpose(const Eigen::Ref<const Points>& points,
                                             Points& g) const
{
    // Where |d| > M the result is M d / |d|: its derivative is (M / |d|) (I - u u^T) dd
    // + u dM, u = d / |d|, and M = |H_j| of the largest prescription j, whose derivative
    // is its direction (the first such row when several are as large: a subgradient).
    Points d(points.rows(), 3);
    evaluate_unlimited(points, d);
    const double largest = report_.max_displacement;
    double toward_largest = 0.0;
    for (Eigen::Index i = 0; i < points.rows(); ++i)
    {
        const double n = d.row(i).norm();
        if (!(n > largest))
            continue;
        const Eigen::RowVector3d u = d.row(i) / n;
        const double along = u.dot(g.row(i));
        g.row(i) = (largest / n) * (g.row(i) - along * u);
        toward_largest += along;
    }
    return toward_largest;
}

const FitReport& CorrectedDeformation::report() const
{
    return report_;
}

bool CorrectedDeformation::is_fitted() const
{
    return global_->is_fitted() && correction_.is_fitted();
}

} // namespace meshmorph
