// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: the linear system of the greedy RBF fit (greedy_rbf_deformation.h), a
//! null-space Cholesky factorisation that grows with the centres instead of being refactored
//! each round, and the polynomial-unisolvent set its null space is built on.
#pragma once

#include <vector>

#include <Eigen/LU>

#include "meshmorph/core/types.h"
#include "meshmorph/deform/rbf_evaluator.h"
#include "meshmorph/deform/row_panel_factor.h"

namespace meshmorph::detail
{

//! The growing factorisation of the greedy fit (all in normalised coordinates).
//!
//! The centres are the unisolvent set U followed by the selected ones. The null space of
//! the polynomial block uses the Lagrange basis of U, so adding centres only appends rows
//! and columns to the reduced matrix, and its Cholesky factor grows by row panels.
class IncrementalSystem
{
public:
    //! X: the constraints (normalised), Pall: their polynomial matrix (one row each), U:
    //! rows of Pall forming a unisolvent set (unisolvent_rows). model, X and Pall are
    //! referred to, not copied: they must outlive the system.
    IncrementalSystem(const RbfModel& model, double sign, const Points& X,
                      const Eigen::MatrixXd& Pall, std::vector<Eigen::Index> unisolvent);

    Eigen::Index size() const { return r_; }
    const std::vector<Eigen::Index>& selected() const { return sel_; }
    const std::vector<Eigen::Index>& unisolvent() const { return U_; }

    //! Adds candidates in order; stops at the first one that would make the factor
    //! indefinite (returned in rejected, or -1). Returns the number added.
    Eigen::Index add(const std::vector<Eigen::Index>& cand, Eigen::Index& rejected);

    //! Weights of [U; selected] (rows) and polynomial coefficients for displacements H.
    void solve(const Eigen::MatrixXd& H, Eigen::MatrixXd& W, Eigen::MatrixXd& Q) const;

    //! The transpose of solve(): for adjoints Wbar (rows as W) and Qbar (rows as Q) the
    //! adjoint of H's rows [U; selected] (rows as W), so that for every H
    //! sum(Wbar .* W) + sum(Qbar .* Q) = sum(Hbar .* H[U; selected]). Triangular solves
    //! with the same factor: no centre-by-centre solve.
    Eigen::MatrixXd solve_transpose(const Eigen::MatrixXd& Wbar, const Eigen::MatrixXd& Qbar) const;

    //! Keeps the first r selected centres. The leading r x r block of a Cholesky factor is
    //! the factor of the leading block, so nothing is recomputed.
    void truncate(Eigen::Index r);

    //! (max L_ii / min L_ii)^2 of the factor L: a lower bound of the condition number of the
    //! reduced matrix L L^T (1 before any centre is selected).
    double condition_lower_bound() const;

private:
    double distance2(Eigen::Index i, Eigen::Index j) const
    {
        return (X_.row(i) - X_.row(j)).squaredNorm();
    }
    double phi(Eigen::Index i, Eigen::Index j) const
    {
        return model_.kernel.value(distance2(i, j));
    }
    const RbfModel& model_;
    double sign_;
    const Points& X_;
    const Eigen::MatrixXd& P_;
    std::vector<Eigen::Index> U_;
    Eigen::MatrixXd PU_, AUU_, Lam_, AU_;
    RowPanelFactor factor_; //!< of the selected centres' null-space system
    Eigen::FullPivLU<Eigen::MatrixXd> luT_, lu_;
    std::vector<Eigen::Index> sel_;
    Eigen::Index r_ = 0;
};

//! Rows of P (one per constraint, one column per polynomial term) forming a well-spread
//! unisolvent set: QR with column pivoting on P^T, pivoting on the largest remaining row
//! norm with round-off ties going to the lowest row (first_largest), so that a symmetric
//! mesh gets the same set on every processor. \throw SolverError when the constraints do
//! not determine the polynomial terms.
std::vector<Eigen::Index> unisolvent_rows(const Eigen::MatrixXd& P);

} // namespace meshmorph::detail
