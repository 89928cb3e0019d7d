// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/deform/row_panel_factor.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace meshmorph::detail
{
namespace
{

//! A symmetric positive definite matrix (n x n) with a condition number of about 1e4.
Eigen::MatrixXd spd(Eigen::Index n)
{
    std::srand(7);
    const Eigen::MatrixXd g = Eigen::MatrixXd::Random(n, n);
    return g * g.transpose() + 1e-2 * Eigen::MatrixXd::Identity(n, n);
}

//! L's rows in panels of the given sizes, as the greedy fit appends them.
RowPanelFactor in_panels(const Eigen::MatrixXd& L, const std::vector<Eigen::Index>& sizes)
{
    RowPanelFactor f;
    Eigen::Index first = 0;
    for (const Eigen::Index b : sizes)
    {
        f.append(L.block(first, 0, b, first), L.block(first, first, b, b));
        first += b;
    }
    return f;
}

TEST(RowPanelFactor, substitutions_match_the_whole_factor)
{
    const Eigen::MatrixXd A = spd(50);
    const Eigen::MatrixXd L = A.llt().matrixL();
    const RowPanelFactor f = in_panels(L, {7, 13, 1, 29});
    ASSERT_EQ(f.size(), 50);
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(50, 3);
    Eigen::MatrixXd X = B;
    f.forward(X);
    // Backward error of a triangular solve: a few ulp times |L| |X| (1e-12 leaves room).
    EXPECT_LE((L * X - B).cwiseAbs().maxCoeff(), 1e-12 * (L.cwiseAbs() * X.cwiseAbs()).maxCoeff());
    Eigen::MatrixXd Y = B;
    f.backward(Y);
    EXPECT_LE((L.transpose() * Y - B).cwiseAbs().maxCoeff(),
              1e-12 * (L.transpose().cwiseAbs() * Y.cwiseAbs()).maxCoeff());
    EXPECT_EQ(f.diagonal(), L.diagonal());
}

TEST(RowPanelFactor, truncated_it_is_the_factor_of_the_leading_block)
{
    const Eigen::MatrixXd A = spd(40);
    const Eigen::MatrixXd L = A.llt().matrixL();
    for (const Eigen::Index r : {Eigen::Index(25), Eigen::Index(20), Eigen::Index(0)})
    {
        RowPanelFactor f = in_panels(L, {10, 10, 20});
        f.truncate(r); // 25: inside the last panel; 20: at a panel's end; 0: nothing left
        ASSERT_EQ(f.size(), r);
        if (r > 0) // (maxCoeff of an empty matrix is undefined)
        {
            Eigen::MatrixXd X = Eigen::MatrixXd::Ones(r, 2);
            f.forward(X);
            f.backward(X);
            const Eigen::MatrixXd lead = A.topLeftCorner(r, r);
            // Backward stable: a residual of a few ulp times |A| |X| (1e-12 leaves room).
            EXPECT_LE((lead * X - Eigen::MatrixXd::Ones(r, 2)).cwiseAbs().maxCoeff(),
                      1e-12 * (lead.cwiseAbs() * X.cwiseAbs()).maxCoeff())
                << r;
        }
        // Growing again after a truncation continues the same factor.
        f.append(L.block(r, 0, 40 - r, r), L.block(r, r, 40 - r, 40 - r));
        EXPECT_EQ(f.diagonal(), L.diagonal()) << r;
    }
}

TEST(RowPanelFactor, many_columns_are_solved_in_blocks_with_bits_independent_of_threads)
{
    // 300 x 200: blocks of forward_block columns, run on OpenMP's threads when there are
    // several; the greedy fit's centres follow these bits, so the thread count must not.
    const Eigen::Index n = 300, m = 3 * RowPanelFactor::forward_block + 8;
    const Eigen::MatrixXd A = spd(n);
    const Eigen::MatrixXd L = A.llt().matrixL();
    const RowPanelFactor f = in_panels(L, {100, 150, 50});
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, m);
    Eigen::MatrixXd X = B;
    f.forward(X);
    EXPECT_LE((L * X - B).cwiseAbs().maxCoeff(), 1e-12 * (L.cwiseAbs() * X.cwiseAbs()).maxCoeff());
#ifdef _OPENMP
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    Eigen::MatrixXd X1 = B;
    f.forward(X1);
    omp_set_num_threads(threads);
    EXPECT_TRUE(X1 == X) << "differs from one thread by " << (X1 - X).cwiseAbs().maxCoeff();
#endif
}

TEST(RowPanelFactor, blocks_of_the_wrong_size_are_a_logic_error)
{
    RowPanelFactor f;
    EXPECT_THROW(f.append(Eigen::MatrixXd(2, 1), Eigen::MatrixXd(2, 2)), std::logic_error);
    Eigen::MatrixXd X(3, 1);
    EXPECT_THROW(f.forward(X), std::logic_error);
}

} // namespace
} // namespace meshmorph::detail
