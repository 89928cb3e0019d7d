// SPDX-License-Identifier: GPL-3.0-or-later
// Greedy RBF refinement: the fit's stages and rounds. The growing factorisation is
// greedy_system.h's, the choice of centres greedy_centres.h's (see the header for the
// formulation).
#include "meshmorph/deform/greedy_rbf_deformation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/greedy_centres.h"
#include "meshmorph/deform/greedy_system.h"
#include "meshmorph/deform/jump_detection.h"
#include "meshmorph/deform/rbf_evaluator.h"
#include "meshmorph/deform/rbf_setup.h"

namespace meshmorph
{

struct GreedyRbfDeformation::Impl
{
    GreedySettings settings;
    detail::RbfKernelSetup setup;
    detail::RbfModel model;
    FitReport report;
    bool fitted = false;
    bool converged = false;
    bool stopped_growing = false; //!< stopped because the residual grew (see fit())
    Index jump_constraints = 0;   //!< left out of the fit (GreedySettings::jump_slope, jump_width)
    std::vector<Index> centre_indices;
    std::vector<double> history;
    std::vector<double> rms_history;
    //! The model at every constraint of the last fit (values_at_handles()).
    Points values_at_handles;
    //! Per constraint of the last fit: on a jump (handles_left_out()).
    std::vector<char> left_out;
    // Kept after fit for handle_basis() and refit(); system refers to model, merged.centres
    // and P.
    Index num_inputs = 0;
    Points inputs; //!< the constraints given to fit (physical)
    detail::MergedHandles merged;
    Eigen::MatrixXd P;
    std::unique_ptr<detail::IncrementalSystem> system;
};

GreedyRbfDeformation::GreedyRbfDeformation(const GreedySettings& settings)
    : impl_(std::make_unique<Impl>())
{
    impl_->settings = settings;
    impl_->setup = detail::rbf_kernel_setup(settings.rbf);
    if (!(settings.tolerance >= 0.0) || !(settings.rms_tolerance >= 0.0))
        throw InvalidInput("greedy RBF tolerances must be >= 0");
    if (!(settings.spread >= 0.0) || !(settings.jump_slope >= 0.0) || !(settings.jump_width >= 0.0))
        throw InvalidInput("greedy RBF: spread, jumpSlope and jumpWidth must be >= 0 (0: off)");
    if (settings.max_centres < 1 || settings.initial_centres < 0 || settings.batch_size < 0)
        throw InvalidInput("greedy RBF: max_centres must be >= 1, initial_centres and "
                           "batch_size >= 0");
}

GreedyRbfDeformation::~GreedyRbfDeformation() = default;
GreedyRbfDeformation::GreedyRbfDeformation(GreedyRbfDeformation&&) noexcept = default;
GreedyRbfDeformation& GreedyRbfDeformation::operator=(GreedyRbfDeformation&&) noexcept = default;

void GreedyRbfDeformation::prepare(const Eigen::Ref<const Points>& constraints,
                                   const Eigen::Ref<const Points>& displacements)
{
    Impl& d = *impl_;
    d.fitted = false;
    d.converged = false;
    d.stopped_growing = false;
    d.jump_constraints = 0;
    d.history.clear();
    d.rms_history.clear();
    d.report = FitReport{};
    d.report.method = "greedy-rbf";
    d.report.solver = "incremental Lagrange null-space Cholesky";
    d.model = detail::normalised_model(d.setup, constraints);
    d.system.reset();
    d.merged = detail::merge_duplicates(constraints, d.model.normalise(constraints), displacements,
                                        d.settings.rbf.duplicate_tolerance);
    d.num_inputs = Index(constraints.rows());
    d.inputs = constraints;
    detail::choose_polynomial(d.model, d.setup.degree, d.merged.centres,
                              d.settings.rbf.polynomial_rank_tolerance);
    d.P = d.model.polynomial_matrix(d.merged.centres);
}

void GreedyRbfDeformation::set_model(const Eigen::MatrixXd& H)
{
    Impl& d = *impl_;
    const detail::IncrementalSystem& system = *d.system;
    const Points& X = d.merged.centres;
    const Eigen::Index p = d.P.cols();
    Eigen::MatrixXd W, Q;
    system.solve(H, W, Q);
    Points C(p + system.size(), 3);
    for (Eigen::Index a = 0; a < p; ++a)
        C.row(a) = X.row(system.unisolvent()[std::size_t(a)]);
    for (Eigen::Index i = 0; i < system.size(); ++i)
        C.row(p + i) = X.row(system.selected()[std::size_t(i)]);
    d.model.set_centres(C);
    d.model.set_coefficients(W, Q);
}

void GreedyRbfDeformation::fit(const Eigen::Ref<const Points>& constraints,
                               const Eigen::Ref<const Points>& displacements)
{
    detail::check_fit_arguments(constraints, displacements);
    const Stopwatch clock;
    prepare(constraints, displacements);
    Impl& d = *impl_;
    const GreedySettings& s = d.settings;
    const Points& X = d.merged.centres;
    const Eigen::MatrixXd H = d.merged.displacements;
    const Eigen::Index N = X.rows(), p = d.P.cols();
    Points Xphys(N, 3);
    for (Eigen::Index i = 0; i < N; ++i)
        Xphys.row(i) = constraints.row(d.merged.first[std::size_t(i)]);

    const std::vector<Eigen::Index> U = detail::unisolvent_rows(d.P);
    detail::CentreMarks marks(N);
    const detail::JumpBand band = detail::mark_jumps(Xphys, H, s, marks, d.jump_constraints);
    if (d.jump_constraints > 0)
        detail::log_jumps(d.jump_constraints, band, s);
    for (Eigen::Index u : U)
        marks.is_centre[std::size_t(u)] = 1;
    const Eigen::Index budget = std::max<Eigen::Index>(s.max_centres, p);
    const Eigen::Index n0 =
        std::min({s.initial_centres > 0 ? s.initial_centres
                                        : std::max<Eigen::Index>(p, std::min<Eigen::Index>(20, N)),
                  N, budget});
    const std::vector<Eigen::Index> initial = detail::farthest_point_centres(X, H, U, n0, marks);
    d.system = std::make_unique<detail::IncrementalSystem>(d.model, d.setup.sign, X, d.P, U);
    detail::add_centres(*d.system, initial, marks);
    Points round_values; // the model at the kept handles after the last round
    const Eigen::Index iterations = refine(Xphys, H, budget, marks, clock, round_values);
    d.left_out.resize(std::size_t(d.num_inputs));
    for (std::size_t i = 0; i < d.left_out.size(); ++i)
        d.left_out[i] = marks.jump[std::size_t(d.merged.representative[i])];
    finish_report(constraints, displacements, Index(iterations), budget, round_values);
}

Eigen::Index GreedyRbfDeformation::refine(const Points& Xphys, const Eigen::MatrixXd& H,
                                          Eigen::Index budget, detail::CentreMarks& marks,
                                          const Stopwatch& clock, Points& got)
{
    Impl& d = *impl_;
    const GreedySettings& s = d.settings;
    detail::IncrementalSystem& system = *d.system;
    const Eigen::Index N = Xphys.rows(), p = d.P.cols();
    const double max_disp = H.rows() > 0 ? H.rowwise().norm().maxCoeff() : 0.0;
    const double rel = 1.0 / std::max(max_disp, 1e-300);
    got.resize(N, 3);
    Eigen::Index iterations = 0;
    double best_rms = std::numeric_limits<double>::infinity();
    Eigen::Index best_size = 0;
    while (true)
    {
        set_model(H);
        d.model.evaluate(Xphys, got);
        Eigen::Index n_fitted = 0;
        const Eigen::VectorXd err = detail::fitted_residuals(got, H, marks, n_fitted);
        const double max_err = err.maxCoeff();
        const double rms =
            std::sqrt(err.squaredNorm() / double(std::max<Eigen::Index>(n_fitted, 1)));
        d.history.push_back(max_err);
        d.rms_history.push_back(rms);
        log::info() << "    greedy RBF round " << iterations << ": " << p + system.size()
                    << " centres, max residual " << max_err * rel << ", rms " << rms * rel
                    << " (relative), " << clock.seconds() << " s";
        if (max_err <= s.tolerance * max_disp && rms <= s.rms_tolerance * max_disp)
        {
            d.converged = true;
            return iterations;
        }
        if (rms > best_rms && !(s.spread > 0.0))
        {
            // More centres made the fit worse: the data vary too sharply for a global
            // interpolant at this resolution (a moving wall touching a fixed one), and the
            // interpolant oscillates. Keep the best round; the caller's local correction
            // (CorrectedDeformation) takes up the rest.
            system.truncate(best_size);
            set_model(H);
            got.resize(0, 3); // the values of a model no longer kept
            d.stopped_growing = true;
            d.history.pop_back(); // the histories end with the model kept
            d.rms_history.pop_back();
            log::info() << "    greedy RBF: the rms residual grew (" << rms * rel << " > "
                        << best_rms * rel << "): keeping the " << p + best_size
                        << " centres of the best round";
            return iterations - 1;
        }
        if (rms <= best_rms)
        {
            best_rms = rms;
            best_size = system.size();
        }
        std::vector<Eigen::Index> cand = detail::candidates(err, marks);
        if (cand.empty())
        {
            d.converged = true; // every constraint is a centre: interpolated exactly
            return iterations;
        }
        const Eigen::Index centres = p + system.size();
        if (centres >= budget)
            return iterations;
        cand = detail::next_batch(std::move(cand), err, max_err, max_disp, s, d.merged.centres,
                                  system, centres, budget - centres);
        for (Eigen::Index j : cand)
            marks.is_centre[std::size_t(j)] = 1;
        detail::add_centres(system, cand, marks);
        ++iterations;
    }
}

//! The model at every constraint. A constraint that is the point of its kept handle takes
//! the last round's value there (the evaluation of the same point by the same model, bit
//! for bit); the others (merged duplicates, or all after a truncated refinement) are
//! evaluated. This spares the morph an evaluation at every constraint (1e8 kernel values
//! on the motorBike).
Points GreedyRbfDeformation::values_at_constraints(const Impl& d,
                                                   const Eigen::Ref<const Points>& constraints,
                                                   const Points& round_values)
{
    const Eigen::Index m = constraints.rows();
    Points values(m, 3);
    std::vector<Eigen::Index> rest;
    const bool have_round = round_values.rows() == Eigen::Index(d.merged.first.size());
    for (Eigen::Index c = 0; c < m; ++c)
    {
        const Index kept = d.merged.representative[std::size_t(c)];
        if (have_round && d.merged.first[std::size_t(kept)] == c)
            values.row(c) = round_values.row(kept);
        else
            rest.push_back(c);
    }
    if (rest.empty())
        return values;
    Points at(Eigen::Index(rest.size()), 3), got(Eigen::Index(rest.size()), 3);
    for (std::size_t k = 0; k < rest.size(); ++k)
        at.row(Eigen::Index(k)) = constraints.row(rest[k]);
    d.model.evaluate(at, got);
    for (std::size_t k = 0; k < rest.size(); ++k)
        values.row(rest[k]) = got.row(Eigen::Index(k));
    return values;
}

void GreedyRbfDeformation::refit(const Eigen::Ref<const Points>& displacements)
{
    Impl& d = *impl_;
    if (!d.fitted)
        throw InvalidInput("greedy RBF: refit before fit");
    if (Index(displacements.rows()) != d.num_inputs)
        throw InvalidInput("greedy RBF refit: " + std::to_string(displacements.rows()) +
                           " displacements for " + std::to_string(d.num_inputs) + " constraints");
    detail::require_finite(displacements, "greedy RBF refit: displacement");
    // Coincident constraints were merged into their first; the others must agree with it,
    // as at the fit.
    for (Index c = 0; c < d.num_inputs; ++c)
    {
        const Index first = d.merged.first[std::size_t(d.merged.representative[std::size_t(c)])];
        if (displacements.row(c) != displacements.row(first))
            throw InvalidInput("greedy RBF refit: constraints " + std::to_string(first) + " and " +
                               std::to_string(c) + " coincide but their displacements differ");
    }
    for (Eigen::Index k = 0; k < d.merged.displacements.rows(); ++k)
        d.merged.displacements.row(k) = displacements.row(d.merged.first[std::size_t(k)]);
    set_model(d.merged.displacements);
    d.values_at_handles = values_at_constraints(d, d.inputs, Points(0, 3));
    detail::residual_report(d.values_at_handles, displacements, d.report);
    if (d.jump_constraints > 0)
    {
        double fitted = 0.0; // the residual over the constraints the global part fits
        for (Index c = 0; c < d.num_inputs; ++c)
            if (!d.left_out[std::size_t(c)])
                fitted =
                    std::max(fitted, (d.values_at_handles.row(c) - displacements.row(c)).norm());
        d.report.max_fitted_residual = fitted;
    }
}

const std::vector<char>* GreedyRbfDeformation::handles_left_out() const
{
    return impl_->fitted && impl_->jump_constraints > 0 ? &impl_->left_out : nullptr;
}

const Points* GreedyRbfDeformation::values_at_handles() const
{
    return impl_->fitted ? &impl_->values_at_handles : nullptr;
}

void GreedyRbfDeformation::finish_report(const Eigen::Ref<const Points>& constraints,
                                         const Eigen::Ref<const Points>& displacements,
                                         Index iterations, Eigen::Index budget,
                                         const Points& round_values)
{
    Impl& d = *impl_;
    const detail::IncrementalSystem& system = *d.system;
    const Eigen::Index p = d.P.cols();
    d.centre_indices.clear();
    for (Eigen::Index a = 0; a < p; ++a)
        d.centre_indices.push_back(
            d.merged.first[std::size_t(system.unisolvent()[std::size_t(a)])]);
    for (Eigen::Index j : system.selected())
        d.centre_indices.push_back(d.merged.first[std::size_t(j)]);
    d.fitted = true;
    d.report.num_handles = Index(d.merged.centres.rows());
    d.report.num_merged_duplicates = Index(constraints.rows() - d.merged.centres.rows());
    d.report.num_centres = Index(d.centre_indices.size());
    d.report.polynomial_terms = Index(p);
    d.report.iterations = iterations;
    d.report.condition_estimate = system.condition_lower_bound();
    d.values_at_handles = values_at_constraints(d, constraints, round_values);
    detail::residual_report(d.values_at_handles, displacements, d.report);
    d.report.jump_constraints = d.jump_constraints;
    if (d.jump_constraints > 0 && !d.history.empty())
        d.report.max_fitted_residual = d.history.back(); // the kept round's, over the others
    if (!d.converged && !d.stopped_growing)
    {
        const double max_disp = d.merged.displacements.rows() > 0
                                    ? d.merged.displacements.rowwise().norm().maxCoeff()
                                    : 0.0;
        const double rel = 1.0 / std::max(max_disp, 1e-300);
        // The tolerance applies to the constraints the global part fits (not the jumps).
        const double fitted =
            d.jump_constraints > 0 ? d.report.max_fitted_residual : d.report.max_residual;
        log::info() << "    greedy RBF: the budget of " << budget << " centres (maxCentres) "
                    << "ends the refinement at max residual " << fitted * rel
                    << " (relative, on the constraints it fits; tolerance " << d.settings.tolerance
                    << "; a larger maxCentres refines further)";
    }
}

void GreedyRbfDeformation::write_field(FieldWriter& out) const
{
    if (!impl_->fitted)
        throw InvalidInput("greedy RBF: write_field before fit");
    out.put(FieldKind::rbf);
    impl_->model.write(out);
}

void GreedyRbfDeformation::evaluate(const Eigen::Ref<const Points>& points,
                                    Eigen::Ref<Points> out) const
{
    detail::check_evaluate_arguments(impl_->fitted, points, out, "greedy RBF");
    impl_->model.evaluate(points, out);
}

const FitReport& GreedyRbfDeformation::report() const
{
    return impl_->report;
}
bool GreedyRbfDeformation::is_fitted() const
{
    return impl_->fitted;
}
bool GreedyRbfDeformation::converged() const
{
    return impl_->converged;
}
const std::vector<Index>& GreedyRbfDeformation::centre_indices() const
{
    return impl_->centre_indices;
}
const std::vector<double>& GreedyRbfDeformation::history() const
{
    return impl_->history;
}
const std::vector<double>& GreedyRbfDeformation::rms_history() const
{
    return impl_->rms_history;
}
bool GreedyRbfDeformation::stopped_growing() const
{
    return impl_->stopped_growing;
}
Index GreedyRbfDeformation::jump_constraints() const
{
    return impl_->jump_constraints;
}

Eigen::MatrixXd GreedyRbfDeformation::handle_basis(const Eigen::Ref<const Points>& points) const
{
    const Impl& d = *impl_;
    if (!d.fitted)
        throw InvalidInput("greedy RBF: handle_basis() called before fit()");
    detail::require_finite(points, "greedy RBF handle basis: point");
    const detail::IncrementalSystem& system = *d.system;
    const Eigen::Index p = d.P.cols();
    const Eigen::Index c = p + system.size();
    // Unit displacement of each centre in turn (rows of the merged constraints).
    std::vector<Eigen::Index> rows(system.unisolvent());
    rows.insert(rows.end(), system.selected().begin(), system.selected().end());
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(d.merged.centres.rows(), c);
    for (Eigen::Index i = 0; i < c; ++i)
        E(rows[std::size_t(i)], i) = 1.0;
    Eigen::MatrixXd W, Q;
    system.solve(E, W, Q);
    const Points xn = d.model.normalise(points);
    Eigen::MatrixXd Bc = d.model.kernel_matrix(xn) * W;
    if (p > 0)
        Bc.noalias() += d.model.polynomial_matrix(xn) * Q;
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(points.rows(), d.num_inputs);
    for (Eigen::Index i = 0; i < c; ++i)
        B.col(d.merged.first[std::size_t(rows[std::size_t(i)])]) = Bc.col(i);
    return B;
}

Points GreedyRbfDeformation::transpose(const Eigen::Ref<const Points>& points,
                                       const Eigen::Ref<const Points>& weights) const
{
    const Impl& d = *impl_;
    detail::check_transpose_arguments(d.fitted, points, weights, "greedy RBF");
    // d(x) = K(x) W H_c + P(x) Q H_c for the centres' displacements H_c, so the adjoint of
    // H_c is W^T (K^T G) + Q^T (P^T G): the transposed solve of K^T G and P^T G.
    const detail::IncrementalSystem& system = *d.system;
    Eigen::MatrixXd KtG, PtG;
    d.model.transpose_sums(points, weights, KtG, PtG);
    const Eigen::MatrixXd centres = system.solve_transpose(KtG, PtG);
    std::vector<Eigen::Index> rows(system.unisolvent());
    rows.insert(rows.end(), system.selected().begin(), system.selected().end());
    Points out = Points::Zero(d.num_inputs, 3);
    for (std::size_t i = 0; i < rows.size(); ++i)
        out.row(d.merged.first[std::size_t(rows[i])]) = centres.row(Eigen::Index(i));
    return out;
}

} // namespace meshmorph
