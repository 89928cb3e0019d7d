// SPDX-License-Identifier: GPL-3.0-or-later
// Forward and back substitution over row panels: one product with everything left of a
// panel and one triangular solve with its diagonal block each (blocked substitution).
#include "meshmorph/deform/row_panel_factor.h"

#include <algorithm>
#include <stdexcept>

#include "meshmorph/deform/dense_kernels.h"

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
    // Columns are independent: blocks of a fixed width, on OpenMP's threads, each block on
    // one thread. The blocks do not depend on the thread count, so neither do the bits.
    use_one_eigen_thread();
    const Eigen::Index n = X.cols();
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
    if (columns == 0)
        return;
    for (const Panel& p : panels_)
    {
        const Eigen::Index ld = p.entries.rows();
        auto xp = dense_block(x + p.first, p.rows, columns, size_);
        if (p.first > 0) // X_p -= L_p,left X_0..first
            subtract_product(xp, dense_block(p.entries.data(), p.rows, p.first, ld),
                             dense_block(static_cast<const double*>(x), p.first, columns, size_));
        solve_lower(dense_block(p.entries.data() + p.first * ld, p.rows, p.rows, ld), xp);
    }
}

void RowPanelFactor::backward(Eigen::MatrixXd& X) const
{
    if (X.rows() != size_)
        throw std::logic_error("RowPanelFactor::backward: wrong number of rows");
    const Eigen::Index m = X.cols();
    if (m == 0)
        return;
    for (auto k = panels_.rbegin(); k != panels_.rend(); ++k)
    {
        auto xk = dense_block(X.data() + k->first, k->rows, m, size_);
        // X_k -= sum over the later panels j of (L_j's columns of panel k)^T X_j
        for (auto j = panels_.rbegin(); j != k; ++j)
        {
            const Eigen::Index ldj = j->entries.rows();
            subtract_transposed_product(
                xk, dense_block(j->entries.data() + k->first * ldj, j->rows, k->rows, ldj),
                dense_block(static_cast<const double*>(X.data()) + j->first, j->rows, m, size_));
        }
        const Eigen::Index ld = k->entries.rows();
        solve_lower_transposed(dense_block(k->entries.data() + k->first * ld, k->rows, k->rows, ld),
                               xk);
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
