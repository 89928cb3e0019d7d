// SPDX-License-Identifier: GPL-3.0-or-later
// Forward and back substitution over row panels: one dgemm with everything left of a panel
// and one dtrsm with its diagonal block each (blocked substitution, BLAS level 3).
#include "meshmorph/deform/row_panel_factor.h"

#include <algorithm>
#include <stdexcept>

#include "meshmorph/deform/lapack.h"

namespace meshmorph::detail
{

void RowPanelFactor::append(const Eigen::MatrixXd& below, const Eigen::MatrixXd& diagonal)
{
    const Eigen::Index b = diagonal.rows();
    if (below.rows() != b || below.cols() != size_ || diagonal.cols() != b)
        throw std::logic_error("RowPanelFactor::append: blocks of the wrong size");
    if (b == 0)
        return;
    Panel panel{size_, b, Eigen::MatrixXd(b, size_ + b)};
    panel.entries.leftCols(size_) = below;
    panel.entries.rightCols(b).triangularView<Eigen::Lower>() =
        diagonal.triangularView<Eigen::Lower>();
    panels_.push_back(std::move(panel));
    size_ += b;
}

void RowPanelFactor::truncate(Eigen::Index r)
{
    if (r >= size_)
        return;
    while (!panels_.empty() && panels_.back().first >= r)
        panels_.pop_back();
    if (!panels_.empty())
    {
        // The kept rows of the last panel, compacted: append() and the substitutions take a
        // panel's leading dimension to be its row count.
        Panel& last = panels_.back();
        const Eigen::Index rows = r - last.first;
        const Eigen::MatrixXd kept = last.entries.topLeftCorner(rows, r);
        last.entries = kept;
        last.rows = rows;
    }
    size_ = r;
}

void RowPanelFactor::forward(Eigen::MatrixXd& X) const
{
    if (X.rows() != size_)
        throw std::logic_error("RowPanelFactor::forward: wrong number of rows");
    // Columns are independent: blocks of a fixed width, on OpenMP's threads, each block by
    // single-threaded BLAS. The blocks do not depend on the thread count, so neither do
    // the bits.
    const Eigen::Index n = X.cols();
    (void)lapack_int(n); // dimensions checked here: nothing throws in the parallel loop
    (void)lapack_int(X.rows());
    const Eigen::Index blocks = (n + forward_block - 1) / forward_block;
#pragma omp parallel for schedule(dynamic) if (blocks > 1 && size_ * n > 100000)
    for (Eigen::Index k = 0; k < blocks; ++k)
    {
        const Eigen::Index first = k * forward_block;
        forward_columns(X.data() + first * X.rows(), std::min(forward_block, n - first));
    }
}

void RowPanelFactor::forward_columns(double* x, Eigen::Index columns) const
{
    const int m = lapack_int(columns), ldx = lapack_int(size_);
    const double one = 1.0, minus_one = -1.0;
    if (m == 0)
        return;
    for (const Panel& p : panels_)
    {
        const int b = lapack_int(p.rows), ld = lapack_int(p.entries.rows());
        double* xp = x + p.first;
        if (p.first > 0)
        {
            // X_p -= L_p,left X_0..first
            const int k = lapack_int(p.first);
            dgemm_("N", "N", &b, &m, &k, &minus_one, p.entries.data(), &ld, x, &ldx, &one, xp,
                   &ldx);
        }
        dtrsm_("L", "L", "N", "N", &b, &m, &one, p.entries.data() + p.first * p.entries.rows(), &ld,
               xp, &ldx);
    }
}

void RowPanelFactor::backward(Eigen::MatrixXd& X) const
{
    if (X.rows() != size_)
        throw std::logic_error("RowPanelFactor::backward: wrong number of rows");
    const int m = lapack_int(X.cols()), ldx = lapack_int(X.rows());
    const double one = 1.0, minus_one = -1.0;
    if (m == 0)
        return;
    for (auto k = panels_.rbegin(); k != panels_.rend(); ++k)
    {
        const int b = lapack_int(k->rows);
        double* xk = X.data() + k->first;
        // X_k -= sum over the later panels j of (L_j's columns of panel k)^T X_j
        for (auto j = panels_.rbegin(); j != k; ++j)
        {
            const int bj = lapack_int(j->rows), ldj = lapack_int(j->entries.rows());
            dgemm_("T", "N", &b, &m, &bj, &minus_one,
                   j->entries.data() + k->first * j->entries.rows(), &ldj, X.data() + j->first,
                   &ldx, &one, xk, &ldx);
        }
        const int ld = lapack_int(k->entries.rows());
        dtrsm_("L", "L", "T", "N", &b, &m, &one, k->entries.data() + k->first * k->entries.rows(),
               &ld, xk, &ldx);
    }
}

Eigen::VectorXd RowPanelFactor::diagonal() const
{
    Eigen::VectorXd d(size_);
    for (const Panel& p : panels_)
        for (Eigen::Index i = 0; i < p.rows; ++i)
            d[p.first + i] = p.entries(i, p.first + i);
    return d;
}

} // namespace meshmorph::detail
