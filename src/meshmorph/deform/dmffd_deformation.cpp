// SPDX-License-Identifier: GPL-3.0-or-later
// DM-FFD: clamped pseudo-inverse by LAPACK's divide-and-conquer SVD (dgesdd).
#include "meshmorph/deform/dmffd_deformation.h"

#include <array>
#include <sstream>
#include <utility>
#include <vector>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/lapack.h"

namespace meshmorph
{
namespace
{
//! Halve domain knot spans of axis a that are more than ratio times an adjacent domain span,
//! until none is. Terminates: the smallest span is never split, and a split span is > ratio
//! >= 2 times a neighbour, so its halves stay >= the smallest span; spans are bounded below.
FfdLattice graded(FfdLattice lattice, int a, double ratio)
{
    while (true)
    {
        const std::vector<double>& U = lattice.knots(a);
        const std::size_t n = std::size_t(lattice.counts()[std::size_t(a)]);
        double split = 0.0;
        bool found = false;
        for (std::size_t j = 3; j + 1 < n && !found; ++j)
        {
            const double left = U[j + 1] - U[j], right = U[j + 2] - U[j + 1];
            if (left > ratio * right)
            {
                split = 0.5 * (U[j] + U[j + 1]);
                found = true;
            }
            else if (right > ratio * left)
            {
                split = 0.5 * (U[j + 1] + U[j + 2]);
                found = true;
            }
        }
        if (!found)
            return lattice;
        lattice = lattice.with_inserted_knot(a, split);
    }
}
} // namespace

DmffdDeformation::DmffdDeformation(const DmffdSettings& settings) : settings_(settings)
{
    if (!(settings.clamping >= 0.0 && settings.clamping < 1.0))
        throw InvalidInput("DM-FFD clamping must be in [0, 1) (relative to the largest "
                           "singular value)");
    for (int a = 0; a < 3; ++a)
        if (settings.lattice.control_points[std::size_t(a)] < 4)
            throw InvalidInput("FFD lattice needs at least 4 control points per axis (cubic "
                               "B-splines)");
    if (!(settings.lattice.margin >= 0.0))
        throw InvalidInput("FFD lattice margin must be >= 0");
}

void DmffdDeformation::fit(const Eigen::Ref<const Points>& handles,
                           const Eigen::Ref<const Points>& displacements)
{
    detail::check_fit_arguments(handles, displacements);
    history_.clear();
    converged_ = false;
    fit_lattice(make_lattice(settings_.lattice, handles), handles, displacements);
}

void DmffdDeformation::fit_lattice(const FfdLattice& lattice,
                                   const Eigen::Ref<const Points>& handles,
                                   const Eigen::Ref<const Points>& displacements)
{
    ffd_.reset();
    report_ = FitReport{};
    report_.method = "dmffd";
    report_.solver = "LAPACK dgesdd pseudo-inverse";
    FfdDeformation ffd(lattice, settings_.lattice.outside);
    const Eigen::Index m = handles.rows();
    const Eigen::Index n = ffd.lattice().size();
    const Eigen::Index r = std::min(m, n);
    Eigen::MatrixXd Phi = ffd.basis_matrix(handles);
    Eigen::Index outside = 0;
    for (Eigen::Index i = 0; i < m; ++i)
        if (Phi.row(i).cwiseAbs().maxCoeff() == 0.0)
            ++outside;
    if (outside > 0)
        log::warning() << "DM-FFD: " << outside << " of " << m
                       << " handles lie outside the lattice box and cannot be matched";

    U_.resize(m, r);
    Vt_.resize(r, n);
    Eigen::VectorXd sigma(r);
    const int im = detail::lapack_int(m), in = detail::lapack_int(n), ir = detail::lapack_int(r);
    int info = 0, lwork = -1;
    double query = 0.0;
    std::vector<int> iwork(static_cast<std::size_t>(8 * r));
    dgesdd_("S", &im, &in, Phi.data(), &im, sigma.data(), U_.data(), &im, Vt_.data(), &ir, &query,
            &lwork, iwork.data(), &info);
    lwork = static_cast<int>(query) + 1;
    std::vector<double> work(static_cast<std::size_t>(lwork));
    dgesdd_("S", &im, &in, Phi.data(), &im, sigma.data(), U_.data(), &im, Vt_.data(), &ir,
            work.data(), &lwork, iwork.data(), &info);
    if (info != 0)
        throw SolverError("DM-FFD: SVD of the " + std::to_string(m) + " x " + std::to_string(n) +
                          " basis matrix failed (dgesdd info " + std::to_string(info) + ")");
    inv_sigma_ = Eigen::VectorXd::Zero(r);
    const double smax = r > 0 ? sigma[0] : 0.0;
    Eigen::Index rank = 0;
    double smin_kept = smax;
    for (Eigen::Index i = 0; i < r; ++i)
        if (sigma[i] > settings_.clamping * smax && sigma[i] > 0.0)
        {
            inv_sigma_[i] = 1.0 / sigma[i];
            smin_kept = sigma[i];
            ++rank;
        }
    if (rank == 0)
        throw SolverError("DM-FFD: the basis matrix is zero (all handles outside the lattice?)");
    handles_ = handles;
    ffd_.emplace(std::move(ffd));
    report_.num_handles = static_cast<Index>(m);
    report_.num_centres = static_cast<Index>(n);
    report_.rank = static_cast<Index>(rank);
    report_.condition_estimate = smax / smin_kept;
    refit(displacements);
}

void DmffdDeformation::fit_refined(const Eigen::Ref<const Points>& handles,
                                   const Eigen::Ref<const Points>& displacements,
                                   const DmffdRefinement& refinement)
{
    if (!(refinement.tolerance >= 0.0))
        throw InvalidInput("DM-FFD refinement tolerance must be >= 0");
    if (!(refinement.grading == 0.0 || refinement.grading >= 2.0))
        throw InvalidInput("DM-FFD refinement grading must be 0 (off) or >= 2");
    if (!(refinement.axes[0] || refinement.axes[1] || refinement.axes[2]))
        throw InvalidInput("DM-FFD refinement: no axis enabled for control-plane insertion");
    detail::check_fit_arguments(handles, displacements);
    history_.clear();
    converged_ = false;
    FfdLattice lattice = make_lattice(settings_.lattice, handles);
    Index insertions = 0;
    Points residual(handles.rows(), 3);
    while (true)
    {
        fit_lattice(lattice, handles, displacements);
        history_.push_back(DmffdRefinementStep{lattice.size(), report_.rank, report_.max_residual,
                                               report_.rms_residual});
        if (report_.max_residual <= refinement.tolerance * report_.max_displacement)
        {
            converged_ = true;
            break;
        }
        // Worst handle that the lattice can influence (handles outside the box with the zero
        // policy cannot be helped by refinement).
        evaluate(handles, residual);
        residual -= displacements;
        Eigen::Index worst = -1;
        double worst_error = -1.0;
        Index idx[64];
        double w[64];
        for (Eigen::Index i = 0; i < handles.rows(); ++i)
        {
            const double e = residual.row(i).squaredNorm();
            if (e > worst_error &&
                lattice.basis(handles.row(i).transpose(), settings_.lattice.outside, idx, w) > 0)
            {
                worst_error = e;
                worst = i;
            }
        }
        if (worst < 0)
            break;
        const Vector3 t = lattice.local_coordinates(handles.row(worst).transpose());
        FfdLattice next = lattice;
        for (int a = 0; a < 3; ++a)
            if (refinement.axes[std::size_t(a)])
            {
                const std::pair<double, double> span = next.knot_span(a, t[a]);
                next = next.with_inserted_knot(a, 0.5 * (span.first + span.second));
                if (refinement.grading > 0.0)
                    next = graded(std::move(next), a, refinement.grading);
            }
        if (next.size() > refinement.max_control_points)
            break;
        lattice = std::move(next);
        ++insertions;
    }
    report_.iterations = insertions;
    log::debug() << "DM-FFD refinement: " << insertions << " insertions, " << lattice.size()
                 << " control points, max residual " << report_.max_residual
                 << (converged_ ? " (converged)" : " (budget reached)");
}

void DmffdDeformation::refit(const Eigen::Ref<const Points>& displacements)
{
    if (!ffd_)
        throw InvalidInput("DM-FFD: refit() called before fit()");
    if (displacements.rows() != handles_.rows())
        throw InvalidInput("DM-FFD refit: " + std::to_string(displacements.rows()) +
                           " displacements for " + std::to_string(handles_.rows()) + " handles");
    detail::require_finite(displacements, "DM-FFD displacement");
    const Eigen::MatrixXd t = inv_sigma_.asDiagonal() * (U_.transpose() * displacements);
    const Points C = Vt_.transpose() * t;
    ffd_->set_control_displacements(C);
    detail::residual_report(*this, handles_, displacements, report_);
}

void DmffdDeformation::write_field(FieldWriter& out) const
{
    if (!ffd_)
        throw InvalidInput("DM-FFD: write_field before fit");
    ffd_->write_field(out);
}

void DmffdDeformation::evaluate(const Eigen::Ref<const Points>& points,
                                Eigen::Ref<Points> out) const
{
    detail::check_evaluate_arguments(ffd_.has_value(), points, out, "DM-FFD");
    ffd_->evaluate(points, out);
}

const FfdDeformation& DmffdDeformation::ffd() const
{
    if (!ffd_)
        throw InvalidInput("DM-FFD: not fitted");
    return *ffd_;
}

Eigen::MatrixXd DmffdDeformation::pseudo_inverse() const
{
    if (!ffd_)
        throw InvalidInput("DM-FFD: not fitted");
    return Vt_.transpose() * inv_sigma_.asDiagonal() * U_.transpose();
}

Eigen::MatrixXd DmffdDeformation::handle_basis(const Eigen::Ref<const Points>& points) const
{
    const Eigen::MatrixXd Pinv = pseudo_inverse(); // n x m
    detail::require_finite(points, "DM-FFD handle basis: point");
    const FfdLattice& lattice = ffd_->lattice();
    const FfdOutside outside = ffd_->outside();
    // Columns of Bt = B^T are sums of 64 contiguous columns of Phi^+T.
    const Eigen::MatrixXd PinvT = Pinv.transpose(); // m x n
    Eigen::MatrixXd Bt = Eigen::MatrixXd::Zero(Pinv.cols(), points.rows());
#pragma omp parallel for schedule(dynamic, 64) if (points.rows() > 500)
    for (Eigen::Index i = 0; i < points.rows(); ++i)
    {
        Index idx[64];
        double w[64];
        const int count = lattice.basis(points.row(i).transpose(), outside, idx, w);
        for (int k = 0; k < count; ++k)
            Bt.col(i) += w[k] * PinvT.col(idx[k]);
    }
    Eigen::MatrixXd B = Bt.transpose();
    return B;
}

} // namespace meshmorph
