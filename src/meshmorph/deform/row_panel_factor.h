// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: a lower-triangular Cholesky factor that grows by row panels (the greedy
//! RBF fit's factor).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace meshmorph::detail
{

//! L, n x n lower triangular, stored as the row panels it was grown by: panel k holds rows
//! first_k .. first_k + rows_k - 1 of L, columns 0 .. first_k + rows_k - 1 (its square
//! diagonal block's upper part unused). A panel is written once and never moved, so growing
//! the factor neither copies it nor touches memory beyond its lower triangle (a square
//! array with spare capacity, grown by doubling, touched up to three times as much: pages
//! are faulted whole, and at 1747 centres the capacity had doubled to 2560).
class RowPanelFactor
{
public:
    //! The order n of L (rows kept; truncate() may have dropped some).
    Eigen::Index size() const { return size_; }

    //! Appends the rows [below | diagonal]: below is b x n (the new rows left of the
    //! diagonal), diagonal b x b lower triangular (its upper part is not read).
    void append(const Eigen::MatrixXd& below, const Eigen::MatrixXd& diagonal);

    //! Keeps the leading r x r block, the factor of the leading r x r block of L L^T.
    void truncate(Eigen::Index r);

    //! X := L^-1 X (forward substitution; X has size() rows). Blocks of forward_block
    //! columns run on OpenMP's threads.
    void forward(Eigen::MatrixXd& X) const;
    //! X := L^-T X (back substitution; X has size() rows).
    void backward(Eigen::MatrixXd& X) const;

    //! L's diagonal.
    Eigen::VectorXd diagonal() const;

    //! Columns per block of forward().
    static constexpr Eigen::Index forward_block = 64;

private:
    //! forward() on `columns` columns at x (leading dimension size()).
    void forward_columns(double* x, Eigen::Index columns) const;

    struct Panel
    {
        Eigen::Index first = 0;  //!< its first row of L
        Eigen::Index rows = 0;   //!< rows kept (truncate() may lower it)
        Eigen::MatrixXd entries; //!< its rows x (first + its original rows), column-major
    };
    std::vector<Panel> panels_;
    Eigen::Index size_ = 0;
};

} // namespace meshmorph::detail
