// SPDX-License-Identifier: GPL-3.0-or-later
// The greedy RBF fit's null-space system, extended per batch of centres by a triangular
// solve and a Cholesky of the Schur complement, never refactored.
#include "meshmorph/deform/greedy_system.h"

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/tie_break.h"
#include "meshmorph/deform/dense_kernels.h"

namespace meshmorph::detail
{

namespace
{

//! x_i -= A(:, i) . lam + L(:, i) . g for the A.cols() rows of x (A and L: p x n).
void subtract_projection(const Eigen::MatrixXd& A, const Eigen::MatrixXd& L, const double* lam,
                         const double* g, double* x)
{
    const Eigen::Index p = A.rows();
    for (Eigen::Index i = 0; i < A.cols(); ++i)
    {
        const double* a = A.col(i).data();
        const double* l = L.col(i).data();
        double s = 0.0;
        for (Eigen::Index k = 0; k < p; ++k)
            s += a[k] * lam[k] + l[k] * g[k];
        x[i] -= s;
    }
}

} // namespace

IncrementalSystem::IncrementalSystem(const RbfModel& model, double sign, const Points& X,
                                     const Eigen::MatrixXd& Pall,
                                     std::vector<Eigen::Index> unisolvent)
    : model_(model), sign_(sign), X_(X), P_(Pall), U_(std::move(unisolvent))
{
    const Eigen::Index p = P_.cols();
    PU_.resize(p, p);
    AUU_.resize(p, p);
    for (Eigen::Index a = 0; a < p; ++a)
    {
        PU_.row(a) = P_.row(U_[std::size_t(a)]);
        for (Eigen::Index b = 0; b < p; ++b)
            AUU_(a, b) = phi(U_[std::size_t(a)], U_[std::size_t(b)]);
    }
    if (p > 0)
    {
        luT_.compute(PU_.transpose());
        lu_.compute(PU_);
    }
    Lam_.resize(p, 0);
    AU_.resize(p, 0);
}

Eigen::Index IncrementalSystem::add(const std::vector<Eigen::Index>& cand, Eigen::Index& rejected)
{
    rejected = -1;
    const Eigen::Index b = Eigen::Index(cand.size());
    const Eigen::Index p = P_.cols();
    const Eigen::Index r0 = r_;
    if (b == 0)
        return 0;
    Eigen::MatrixXd Lam_n(p, b), AU_n(p, b);
    for (Eigen::Index j = 0; j < b; ++j)
    {
        if (p > 0)
            Lam_n.col(j) = luT_.solve(P_.row(cand[std::size_t(j)]).transpose());
        for (Eigen::Index a = 0; a < p; ++a)
            AU_n(a, j) = phi(U_[std::size_t(a)], cand[std::size_t(j)]);
    }
    // The new columns projected on the null space of the polynomial block: entry (i, j)
    // loses A_i . Lam_j + L_i . G_j with G = AU_n - AUU Lam_n, where (A_i, L_i) are row
    // i's columns of AU_ and Lam_ (a centre) or of AU_n and Lam_n (a new one). Done
    // column by column beside the kernel values: as products of inner dimension p
    // (Eigen's GEMM, with r0 x b temporaries) it took longer than the kernel values.
    const Eigen::MatrixXd G = p > 0 ? Eigen::MatrixXd(AU_n - AUU_ * Lam_n) : Eigen::MatrixXd(0, b);
    Eigen::MatrixXd Kon(r0, b), Knn(b, b);
    // Columns taken as threads come free: the check before the morph shares the cores.
#pragma omp parallel for schedule(dynamic, 4) if ((r0 + b) * b > 20000)
    for (Eigen::Index j = 0; j < b; ++j)
    {
        // Squared distances first, then the kernel over the column in one vectorised
        // pass: the same values as phi() element by element.
        for (Eigen::Index i = 0; i < r0; ++i)
            Kon(i, j) = distance2(sel_[std::size_t(i)], cand[std::size_t(j)]);
        for (Eigen::Index i = 0; i < b; ++i)
            Knn(i, j) = distance2(cand[std::size_t(i)], cand[std::size_t(j)]);
        model_.kernel.values_in_place(Kon.col(j).data(), std::size_t(r0));
        model_.kernel.values_in_place(Knn.col(j).data(), std::size_t(b));
        if (p > 0)
        {
            subtract_projection(AU_, Lam_, Lam_n.col(j).data(), G.col(j).data(), Kon.col(j).data());
            subtract_projection(AU_n, Lam_n, Lam_n.col(j).data(), G.col(j).data(),
                                Knn.col(j).data());
        }
        Kon.col(j) *= sign_;
        Knn.col(j) *= sign_;
    }
    factor_.forward(Kon);
    // The Schur complement S = Knn - Kon^T Kon (lower triangle) and its Cholesky factor,
    // on one thread (dense_kernels.h): the last bits of S, then the centres chosen from
    // residuals amplified by the condition number, must not follow the thread count or the
    // processor's BLAS kernel.
    Eigen::MatrixXd S = Knn;
    if (r0 > 0)
        subtract_gram_lower(dense_block(S.data(), b, b, b), dense_block(Kon.data(), r0, b, r0));
    const Eigen::Index failed = cholesky_lower(dense_block(S.data(), b, b, b));
    Eigen::Index keep = b;
    if (failed >= 0)
    {
        keep = failed;
        rejected = cand[std::size_t(keep)];
    }
    factor_.append(Kon.leftCols(keep).transpose(), S.topLeftCorner(keep, keep));
    Lam_.conservativeResize(p, r0 + keep);
    AU_.conservativeResize(p, r0 + keep);
    Lam_.rightCols(keep) = Lam_n.leftCols(keep);
    AU_.rightCols(keep) = AU_n.leftCols(keep);
    for (Eigen::Index j = 0; j < keep; ++j)
        sel_.push_back(cand[std::size_t(j)]);
    r_ = r0 + keep;
    return keep;
}

void IncrementalSystem::solve(const Eigen::MatrixXd& H, Eigen::MatrixXd& W,
                              Eigen::MatrixXd& Q) const
{
    const Eigen::Index p = P_.cols();
    const Eigen::Index nc = H.cols();
    Eigen::MatrixXd HU(p, nc);
    for (Eigen::Index a = 0; a < p; ++a)
        HU.row(a) = H.row(U_[std::size_t(a)]);
    Eigen::MatrixXd Y(r_, nc);
    for (Eigen::Index i = 0; i < r_; ++i)
        Y.row(i) = H.row(sel_[std::size_t(i)]);
    if (p > 0)
        Y -= Lam_.transpose() * HU;
    Y *= sign_;
    factor_.forward(Y);
    factor_.backward(Y);
    W.resize(p + r_, nc);
    W.bottomRows(r_) = Y;
    if (p > 0)
    {
        W.topRows(p) = -Lam_ * Y;
        Q = lu_.solve(HU - AUU_ * W.topRows(p) - AU_ * Y);
    }
    else
    {
        Q.resize(0, nc);
    }
}

Eigen::MatrixXd IncrementalSystem::solve_transpose(const Eigen::MatrixXd& Wbar,
                                                   const Eigen::MatrixXd& Qbar) const
{
    // solve() backwards: Q = PU^-1 (HU - AUU W_top - AU Y), W_top = -Lam Y,
    // Y = sign (L L^T)^-1 (H_sel - Lam^T HU), HU = H_U.
    const Eigen::Index p = P_.cols();
    const Eigen::Index nc = Wbar.cols();
    Eigen::MatrixXd HUbar = Eigen::MatrixXd::Zero(p, nc);
    Eigen::MatrixXd Ybar = Wbar.bottomRows(r_);
    if (p > 0)
    {
        const Eigen::MatrixXd Z = luT_.solve(Qbar); // PU^-T Qbar
        HUbar += Z;
        const Eigen::MatrixXd Wtop_bar = Wbar.topRows(p) - AUU_.transpose() * Z;
        Ybar -= AU_.transpose() * Z;
        Ybar -= Lam_.transpose() * Wtop_bar;
    }
    // (L L^T)^-1 is symmetric: the same two triangular solves.
    factor_.forward(Ybar);
    factor_.backward(Ybar);
    Ybar *= sign_;
    Eigen::MatrixXd Hbar(p + r_, nc);
    if (p > 0)
        HUbar -= Lam_ * Ybar;
    Hbar.topRows(p) = HUbar;
    Hbar.bottomRows(r_) = Ybar;
    return Hbar;
}

void IncrementalSystem::truncate(Eigen::Index r)
{
    if (r >= r_)
        return;
    sel_.resize(std::size_t(r));
    Lam_.conservativeResize(Lam_.rows(), r);
    AU_.conservativeResize(AU_.rows(), r);
    factor_.truncate(r);
    r_ = r;
}

double IncrementalSystem::condition_lower_bound() const
{
    if (r_ == 0)
        return 1.0;
    const Eigen::VectorXd d = factor_.diagonal().cwiseAbs();
    const double ratio = d.maxCoeff() / d.minCoeff();
    return ratio * ratio;
}

std::vector<Eigen::Index> unisolvent_rows(const Eigen::MatrixXd& P)
{
    Eigen::MatrixXd R = P;
    std::vector<Eigen::Index> rows;
    for (Eigen::Index k = 0; k < P.cols(); ++k)
    {
        const Eigen::Index i = first_largest(R.rowwise().squaredNorm());
        const double norm = R.row(i).norm();
        if (!(norm > 0.0)) // choose_polynomial keeps only terms the constraints determine
            throw SolverError("greedy RBF: the constraints do not determine the polynomial "
                              "terms (too few or degenerate points): set rbf { polynomial none; }");
        const Eigen::VectorXd q = R.row(i).transpose() / norm;
        R -= (R * q) * q.transpose();
        R.row(i).setZero();
        rows.push_back(i);
    }
    return rows;
}

} // namespace meshmorph::detail
