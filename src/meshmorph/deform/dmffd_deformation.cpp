// SPDX-License-Identifier: GPL-3.0-or-later
// DM-FFD: clamped pseudo-inverse by LAPACK's divide-and-conquer SVD (dgesdd).
#include "meshmorph/deform/dmffd_deformation.h"

#include <array>
#include <sstream>
#include <vector>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/deform/lapack.h"

namespace meshmorph
{

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
    ffd_.reset();
    report_ = FitReport{};
    report_.method = "dmffd";
    report_.solver = "LAPACK dgesdd pseudo-inverse";
    FfdDeformation ffd(make_lattice(settings_.lattice, handles), settings_.lattice.outside);
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
    detail::check_fit_arguments(handles, displacements);
    if (!settings_.lattice.box)
        settings_.lattice.box = make_lattice(settings_.lattice, handles).box();
    Index refinements = 0;
    while (true)
    {
        fit(handles, displacements);
        if (report_.max_residual <= refinement.tolerance * report_.max_displacement)
            break;
        std::array<int, 3>& n = settings_.lattice.control_points;
        int axis = 0;
        double spacing = -1.0;
        for (int a = 0; a < 3; ++a)
        {
            const double h = settings_.lattice.box->axes.col(a).norm() / (n[std::size_t(a)] - 3);
            if (h > spacing)
            {
                spacing = h;
                axis = a;
            }
        }
        std::array<int, 3> next = n;
        next[std::size_t(axis)] = 2 * n[std::size_t(axis)] - 3;
        if (Index(next[0]) * next[1] * next[2] > refinement.max_control_points)
            break;
        n = next;
        ++refinements;
    }
    report_.iterations = refinements;
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
