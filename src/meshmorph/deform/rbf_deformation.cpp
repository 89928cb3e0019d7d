// SPDX-License-Identifier: GPL-3.0-or-later
// RBF deformation: null-space reduction of Eq. 8 and blocked Cholesky (dense_kernels.h).
#include "meshmorph/deform/rbf_deformation.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/deform/dense_kernels.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/rbf_evaluator.h"
#include "meshmorph/deform/rbf_setup.h"

namespace meshmorph
{

struct RbfDeformation::Impl
{
    RbfSettings settings;
    detail::RbfKernelSetup setup;
    detail::RbfModel model;
    FitReport report;
    bool fitted = false;
    Points handles;           // as given to fit (for residual reports)
    Points values_at_handles; // the field there (values_at_handles())
    detail::MergedHandles merged;
    Eigen::MatrixXd P; // m x p polynomial matrix at the centres
    // dense
    Eigen::MatrixXd A; // Q^T A Q, lower trailing block holds the Cholesky factor
    Eigen::HouseholderQR<Eigen::MatrixXd> qr;
    // sparse (Wendland)
    bool sparse = false;
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt;
    Eigen::MatrixXd U; // A^-1 P
    Eigen::LLT<Eigen::MatrixXd> schur;

    void factor_dense();
    void factor_sparse();
    void solve(const Eigen::MatrixXd& H, Eigen::MatrixXd& W, Eigen::MatrixXd& Q) const;
    void set_displacements(const Eigen::MatrixXd& H);
};

namespace
{

//! What else than near-coincident handles makes a dense kernel system singular: a shape
//! parameter small enough to make the kernel flat (the polyharmonic kernels have none).
std::string flatness_hint(RbfKernel kernel)
{
    switch (kernel)
    {
    case RbfKernel::gaussian:
    case RbfKernel::multiquadric:
    case RbfKernel::inverse_multiquadric:
        return ", or its shape parameter (rbf.shape) makes it too flat";
    default:
        return "";
    }
}

} // namespace

void RbfDeformation::Impl::factor_dense()
{
    const Eigen::Index m = model.num_centres;
    const Eigen::Index p = P.cols();
    const Eigen::Index r = m - p;
    A = model.kernel_matrix(merged.centres);
    if (p > 0)
    {
        qr.compute(P);
        // Q^T A Q in two sweeps over A instead of 4p reflector applications: with the compact
        // WY form Q = I - V T V^T (LAPACK dlarft, forward), Y = A V, Z = V^T Y and
        // W = Y T - V (T^T Z T) / 2, the product is the symmetric rank-2p update
        // A - W V^T - V W^T.
        const Eigen::MatrixXd& qrm = qr.matrixQR();
        const Eigen::VectorXd& tau = qr.hCoeffs();
        Eigen::MatrixXd V = Eigen::MatrixXd::Zero(m, p);
        for (Eigen::Index j = 0; j < p; ++j)
        {
            V(j, j) = 1.0;
            V.col(j).tail(m - j - 1) = qrm.col(j).tail(m - j - 1);
        }
        Eigen::MatrixXd T = Eigen::MatrixXd::Zero(p, p);
        for (Eigen::Index i = 0; i < p; ++i)
        {
            T(i, i) = tau[i];
            if (i > 0)
            {
                const Eigen::VectorXd vtv = V.leftCols(i).transpose() * V.col(i);
                const Eigen::VectorXd tv =
                    T.topLeftCorner(i, i).triangularView<Eigen::Upper>() * vtv;
                T.col(i).head(i) = -tau[i] * tv;
            }
        }
        detail::use_one_eigen_thread(); // the products' bits must not follow the thread count
        const Eigen::MatrixXd Y = A * V;
        const Eigen::MatrixXd Z = V.transpose() * Y;
        Eigen::MatrixXd WV(m, 2 * p), VW(m, 2 * p);
        WV.leftCols(p) = Y * T - 0.5 * V * (T.transpose() * Z * T);
        WV.rightCols(p) = V;
        VW.leftCols(p) = V;
        VW.rightCols(p) = WV.leftCols(p);
        A.noalias() -= WV * VW.transpose();
    }
    report.solver = p > 0 ? "null-space QR + blocked Cholesky" : "blocked Cholesky";
    report.condition_estimate = 1.0;
    if (r == 0)
        return;
    auto B = detail::dense_block(A.data() + p * m + p, r, r, m);
    if (setup.sign < 0)
    {
#pragma omp parallel for schedule(static) if (r > 500)
        for (Eigen::Index j = 0; j < r; ++j)
            for (Eigen::Index i = j; i < r; ++i)
                B(i, j) = -B(i, j);
    }
    const double norm = detail::symmetric_norm1(B);
    if (const Eigen::Index failed = detail::cholesky_lower(B); failed >= 0)
    {
        std::ostringstream s;
        s << "RBF (" << to_string(settings.kernel) << "): the reduced " << r << " x " << r
          << " system is not " << (setup.sign < 0 ? "negative" : "positive")
          << " definite (Cholesky failed at column " << failed + 1
          << "): the handles nearly coincide for this kernel" << flatness_hint(settings.kernel);
        throw SolverError(s.str());
    }
    const double rcond = detail::cholesky_reciprocal_condition(B, norm);
    report.condition_estimate = rcond > 0.0 ? 1.0 / rcond : std::numeric_limits<double>::infinity();
}

void RbfDeformation::Impl::factor_sparse()
{
    const Eigen::Index m = model.num_centres;
    const double rho = model.kernel.support;
    std::vector<Eigen::Triplet<double>> triplets;
    const Points& c = merged.centres;
    for (Eigen::Index i = 0; i < m; ++i)
        model.grid.for_each_near(c(i, 0), c(i, 1), c(i, 2),
                                 [&](Eigen::Index j)
                                 {
                                     const double r2 = (c.row(i) - c.row(j)).squaredNorm();
                                     if (r2 < rho * rho)
                                         triplets.emplace_back(i, j, model.kernel.value(r2));
                                 });
    Eigen::SparseMatrix<double> K(m, m);
    K.setFromTriplets(triplets.begin(), triplets.end());
    llt.compute(K);
    if (llt.info() != Eigen::Success)
        throw SolverError("RBF (wendlandC2): sparse Cholesky failed: the matrix is not "
                          "numerically positive definite (handles nearly coincide?)");
    const Eigen::SparseMatrix<double> L = llt.matrixL();
    const Eigen::VectorXd d = L.diagonal().cwiseAbs2();
    report.condition_estimate = d.maxCoeff() / d.minCoeff();
    report.solver = "sparse SimplicialLLT (" + std::to_string(K.nonZeros()) + " nonzeros)";
    if (P.cols() > 0)
    {
        U = llt.solve(P);
        schur.compute(P.transpose() * U);
        if (schur.info() != Eigen::Success)
            throw SolverError("RBF (wendlandC2): polynomial Schur complement is singular");
        report.solver += " + Schur complement for the polynomial";
    }
}

void RbfDeformation::Impl::solve(const Eigen::MatrixXd& H, Eigen::MatrixXd& W,
                                 Eigen::MatrixXd& Qc) const
{
    const Eigen::Index m = model.num_centres;
    const Eigen::Index p = P.cols();
    if (sparse)
    {
        const Eigen::MatrixXd a = llt.solve(H);
        if (p > 0)
        {
            Qc = schur.solve(P.transpose() * a);
            W = a - U * Qc;
        }
        else
        {
            Qc.resize(0, H.cols());
            W = a;
        }
        return;
    }
    const Eigen::Index r = m - p;
    Eigen::MatrixXd G = H;
    if (p > 0)
        G.applyOnTheLeft(qr.householderQ().adjoint());
    Eigen::MatrixXd Y = setup.sign * G.bottomRows(r);
    if (r > 0)
    {
        const auto L = detail::dense_block(A.data() + p * m + p, r, r, m);
        auto y = detail::dense_block(Y.data(), r, Y.cols(), r);
        detail::solve_lower(L, y);
        detail::solve_lower_transposed(L, y);
    }
    W.resize(m, H.cols());
    W.topRows(p).setZero();
    W.bottomRows(r) = Y;
    if (p > 0)
    {
        W.applyOnTheLeft(qr.householderQ());
        const Eigen::MatrixXd rhs = G.topRows(p) - A.block(0, p, p, r) * Y;
        Qc = qr.matrixQR().topLeftCorner(p, p).triangularView<Eigen::Upper>().solve(rhs);
    }
    else
    {
        Qc.resize(0, H.cols());
    }
}

void RbfDeformation::Impl::set_displacements(const Eigen::MatrixXd& H)
{
    Eigen::MatrixXd W, Qc;
    solve(H, W, Qc);
    model.set_coefficients(W, Qc);
    if (settings.refinement_steps <= 0)
        return;
    // Iterative refinement with the same factorisation: solve again for data + (H - d(h)),
    // which cancels the error of an ill-conditioned solve to first order (each step gains
    // about 1 / (cond * eps)). Kept only while it reduces the max residual.
    Points centres_physical = merged.centres * model.scale;
    centres_physical.rowwise() += model.centre.transpose();
    Points got(centres_physical.rows(), 3);
    model.evaluate(centres_physical, got);
    Eigen::MatrixXd R = H - Eigen::MatrixXd(got);
    double error = R.rowwise().norm().maxCoeff();
    const double target = 1e-14 * H.rowwise().norm().maxCoeff();
    Eigen::MatrixXd data = H;
    for (int step = 0; step < settings.refinement_steps && error > target; ++step)
    {
        const Eigen::MatrixXd next = data + R;
        Eigen::MatrixXd W2, Q2;
        solve(next, W2, Q2);
        model.set_coefficients(W2, Q2);
        model.evaluate(centres_physical, got);
        const Eigen::MatrixXd R2 = H - Eigen::MatrixXd(got);
        const double error2 = R2.rowwise().norm().maxCoeff();
        if (!(error2 < error))
        {
            model.set_coefficients(W, Qc); // no gain: keep the previous solution
            break;
        }
        W = W2;
        Qc = Q2;
        data = next;
        R = R2;
        error = error2;
    }
}

RbfDeformation::RbfDeformation(const RbfSettings& settings) : impl_(std::make_unique<Impl>())
{
    impl_->settings = settings;
    impl_->setup = detail::rbf_kernel_setup(settings);
}

RbfDeformation::~RbfDeformation() = default;
RbfDeformation::RbfDeformation(RbfDeformation&&) noexcept = default;
RbfDeformation& RbfDeformation::operator=(RbfDeformation&&) noexcept = default;

void RbfDeformation::fit(const Eigen::Ref<const Points>& handles,
                         const Eigen::Ref<const Points>& displacements)
{
    detail::check_fit_arguments(handles, displacements);
    Impl& d = *impl_;
    d.fitted = false;
    d.report = FitReport{};
    d.report.method = "rbf";
    d.model = detail::normalised_model(d.setup, handles);
    const Points normalised = d.model.normalise(handles);
    d.merged = detail::merge_duplicates(handles, normalised, displacements,
                                        d.settings.duplicate_tolerance);
    d.handles = handles;
    detail::choose_polynomial(d.model, d.setup.degree, d.merged.centres,
                              d.settings.polynomial_rank_tolerance);
    d.P = d.model.polynomial_matrix(d.merged.centres);
    d.model.set_centres(d.merged.centres);
    d.sparse = d.setup.params.type == detail::KernelType::wendland_c2;
    if (!d.sparse && d.merged.centres.rows() > d.settings.max_dense_centres)
        throw InvalidInput(
            "RBF: " + std::to_string(d.merged.centres.rows()) +
            " centres exceed max_dense_centres = " + std::to_string(d.settings.max_dense_centres) +
            " (the dense matrix "
            "would need " +
            std::to_string(8.0 * double(d.merged.centres.rows()) * double(d.merged.centres.rows()) /
                           1e9) +
            " GB); use the greedy RBF or the Wendland kernel");
    if (d.sparse)
        d.factor_sparse();
    else
        d.factor_dense();
    d.set_displacements(d.merged.displacements);
    d.fitted = true;
    d.report.num_handles = static_cast<Index>(d.merged.centres.rows());
    d.report.num_merged_duplicates = static_cast<Index>(handles.rows() - d.merged.centres.rows());
    d.report.num_centres = d.report.num_handles;
    d.report.polynomial_terms = static_cast<Index>(d.P.cols());
    report_residual(displacements);
    check_conditioning();
}

void RbfDeformation::check_conditioning()
{
    Impl& d = *impl_;
    const FitReport& r = d.report;
    const RbfSettings& s = d.settings;
    if (!(r.condition_estimate > s.condition_warning &&
          r.max_residual > s.residual_warning * r.max_displacement))
        return;
    std::ostringstream what;
    what << "RBF (" << to_string(s.kernel) << "): condition estimate " << r.condition_estimate
         << " exceeds " << s.condition_warning << " and the fit misses its handles by up to "
         << r.max_residual / r.max_displacement
         << " of the largest displacement: handles this close together make the system "
            "nearly singular for this kernel";
    if (s.ill_conditioning_is_error)
    {
        d.fitted = false;
        throw SolverError(what.str());
    }
    log::warning() << what.str()
                   << "; the greedy RBF (rbf { greedy { } }) chooses centres that stay apart";
}

void RbfDeformation::refit(const Eigen::Ref<const Points>& displacements)
{
    Impl& d = *impl_;
    if (!d.fitted)
        throw InvalidInput("RBF: refit() called before fit()");
    if (displacements.rows() != d.handles.rows())
        throw InvalidInput("RBF refit: " + std::to_string(displacements.rows()) +
                           " displacements for " + std::to_string(d.handles.rows()) + " handles");
    detail::require_finite(displacements, "RBF refit: displacement");
    Eigen::MatrixXd H(d.merged.centres.rows(), 3);
    for (Eigen::Index i = 0; i < d.handles.rows(); ++i)
        H.row(d.merged.representative[std::size_t(i)]) = displacements.row(i);
    // Merged duplicates must still agree.
    double max_disp = 0.0;
    for (Eigen::Index i = 0; i < displacements.rows(); ++i)
        max_disp = std::max(max_disp, displacements.row(i).norm());
    for (Eigen::Index i = 0; i < d.handles.rows(); ++i)
        if ((H.row(d.merged.representative[std::size_t(i)]) - displacements.row(i)).norm() >
            d.settings.duplicate_tolerance * max_disp)
            throw InvalidInput("RBF refit: merged duplicate handle " + std::to_string(i) +
                               " has a displacement different from its twin");
    d.merged.displacements = H;
    d.set_displacements(H);
    report_residual(displacements);
}

void RbfDeformation::report_residual(const Eigen::Ref<const Points>& displacements)
{
    Impl& d = *impl_;
    d.values_at_handles.resize(d.handles.rows(), 3);
    evaluate(d.handles, d.values_at_handles);
    detail::residual_report(d.values_at_handles, displacements, d.report);
}

const Points* RbfDeformation::values_at_handles() const
{
    return impl_->fitted ? &impl_->values_at_handles : nullptr;
}

void RbfDeformation::write_field(FieldWriter& out) const
{
    if (!impl_->fitted)
        throw InvalidInput("RBF: write_field before fit");
    out.put(FieldKind::rbf);
    impl_->model.write(out);
}

void RbfDeformation::evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const
{
    detail::check_evaluate_arguments(impl_->fitted, points, out, "RBF");
    impl_->model.evaluate(points, out);
}

const FitReport& RbfDeformation::report() const
{
    return impl_->report;
}
bool RbfDeformation::is_fitted() const
{
    return impl_->fitted;
}
const RbfSettings& RbfDeformation::settings() const
{
    return impl_->settings;
}

Points RbfDeformation::centres() const
{
    const Impl& d = *impl_;
    Points c = d.merged.centres * d.model.scale;
    c.rowwise() += d.model.centre.transpose();
    return c;
}

Eigen::MatrixXd RbfDeformation::handle_basis(const Eigen::Ref<const Points>& points) const
{
    const Impl& d = *impl_;
    if (!d.fitted)
        throw InvalidInput("RBF: handle_basis() called before fit()");
    detail::require_finite(points, "RBF handle basis: point");
    const Eigen::Index mc = d.model.num_centres;
    Eigen::MatrixXd W, Qc;
    d.solve(Eigen::MatrixXd::Identity(mc, mc), W, Qc);
    const Eigen::Index k = points.rows();
    Eigen::MatrixXd Bc(k, mc);
    const Eigen::Index chunk = 4096;
    for (Eigen::Index i0 = 0; i0 < k; i0 += chunk)
    {
        const Eigen::Index rows = std::min(chunk, k - i0);
        const Points xn = d.model.normalise(points.middleRows(i0, rows));
        Bc.middleRows(i0, rows).noalias() = d.model.kernel_matrix(xn) * W;
        if (Qc.rows() > 0)
            Bc.middleRows(i0, rows).noalias() += d.model.polynomial_matrix(xn) * Qc;
    }
    const Eigen::Index m = d.handles.rows();
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(k, m);
    for (Eigen::Index c = 0; c < mc; ++c)
        B.col(d.merged.first[std::size_t(c)]) = Bc.col(c);
    return B;
}

Points RbfDeformation::transpose(const Eigen::Ref<const Points>& points,
                                 const Eigen::Ref<const Points>& weights) const
{
    const Impl& d = *impl_;
    detail::check_transpose_arguments(d.fitted, points, weights, "RBF");
    // d(x) = K(x) W + P(x) Q with (W, Q) = S H linear in the centres' displacements: the
    // adjoint is S_W^T (K^T G) + S_Q^T (P^T G), S's columns solved for unit displacements
    // (as handle_basis; a direct fit has at most rbf.directLimit centres).
    Eigen::MatrixXd KtG, PtG;
    d.model.transpose_sums(points, weights, KtG, PtG);
    const Eigen::Index mc = d.model.num_centres;
    Eigen::MatrixXd W, Qc;
    d.solve(Eigen::MatrixXd::Identity(mc, mc), W, Qc);
    Eigen::MatrixXd centres = W.transpose() * KtG;
    if (Qc.rows() > 0)
        centres.noalias() += Qc.transpose() * PtG;
    Points out = Points::Zero(d.handles.rows(), 3);
    for (Eigen::Index c = 0; c < mc; ++c)
        out.row(d.merged.first[std::size_t(c)]) = centres.row(c);
    return out;
}

} // namespace meshmorph
