// SPDX-License-Identifier: GPL-3.0-or-later
// The fits' dense kernels (deform/dense_kernels.h) against the definitions they replace
// LAPACK's routines with: the factor reproduces its matrix, a failed factor names dpotrf's
// column, the condition estimate is that of the matrix, and the products and solves are
// what they say.
#include <cmath>
#include <limits>

#include <Eigen/LU>
#include <Eigen/QR>
#include <gtest/gtest.h>

#include "meshmorph/deform/dense_kernels.h"

namespace meshmorph::detail
{
namespace
{

//! A symmetric positive definite n x n matrix with condition number about `condition`:
//! Q diag(1 .. 1/condition) Q^T with a fixed orthogonal Q.
Eigen::MatrixXd spd_matrix(Eigen::Index n, double condition)
{
    const Eigen::MatrixXd random = Eigen::MatrixXd::NullaryExpr(
        n, n, [](Eigen::Index i, Eigen::Index j) { return std::sin(double(7 * i + 13 * j + 1)); });
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(random);
    const Eigen::MatrixXd Q = qr.householderQ();
    Eigen::VectorXd d(n);
    for (Eigen::Index i = 0; i < n; ++i)
        d[i] = std::pow(condition, -double(i) / double(n - 1));
    return Q * d.asDiagonal() * Q.transpose();
}

} // namespace

TEST(DenseKernels, cholesky_reproduces_its_matrix_above_the_block_size)
{
    // 300 > 32: Eigen's blocked algorithm, not only its unblocked one.
    const Eigen::MatrixXd A = spd_matrix(300, 1e6);
    Eigen::MatrixXd L = A;
    ASSERT_EQ(cholesky_lower(dense_block(L.data(), 300, 300, 300)), -1);
    const Eigen::MatrixXd lower = L.triangularView<Eigen::Lower>();
    EXPECT_LT((lower * lower.transpose() - A).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(DenseKernels, a_failed_cholesky_names_the_first_column_that_is_not_definite)
{
    // dpotrf's info - 1: the leading 99 x 99 block is definite, the 100th pivot is not.
    Eigen::MatrixXd A = spd_matrix(150, 10.0);
    A.row(99).setZero();
    A.col(99).setZero();
    A(99, 99) = -1.0;
    EXPECT_EQ(cholesky_lower(dense_block(A.data(), 150, 150, 150)), 99);

    Eigen::MatrixXd B = spd_matrix(40, 10.0);
    B(20, 20) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(cholesky_lower(dense_block(B.data(), 40, 40, 40)), 20) << "a NaN pivot fails";
}

TEST(DenseKernels, the_condition_estimate_is_the_matrix_s_within_the_estimator_s_factor)
{
    // Hager and Higham's 1-norm estimate is a lower bound, within a small factor in practice.
    for (const double condition : {1e2, 1e6, 1e10})
    {
        const Eigen::MatrixXd A = spd_matrix(120, condition);
        const double norm = symmetric_norm1(dense_block(A.data(), 120, 120, 120));
        EXPECT_DOUBLE_EQ(norm, A.cwiseAbs().colwise().sum().maxCoeff());
        Eigen::MatrixXd L = A;
        ASSERT_EQ(cholesky_lower(dense_block(L.data(), 120, 120, 120)), -1);
        const double exact = norm * A.inverse().cwiseAbs().colwise().sum().maxCoeff();
        const double estimate =
            1.0 / cholesky_reciprocal_condition(dense_block(L.data(), 120, 120, 120), norm);
        EXPECT_LE(estimate, exact * (1 + 1e-6)) << condition;
        EXPECT_GE(estimate, exact / 10) << condition;
    }
}

TEST(DenseKernels, products_and_solves_on_blocks_of_larger_arrays)
{
    // Every kernel works on a block with a leading dimension larger than its rows.
    const Eigen::MatrixXd A = spd_matrix(80, 1e3);
    Eigen::MatrixXd big = Eigen::MatrixXd::Zero(100, 80);
    big.topRows(80) = A;
    ASSERT_EQ(cholesky_lower(dense_block(big.data(), 80, 80, 100)), -1);
    const Eigen::MatrixXd L = big.topRows(80).triangularView<Eigen::Lower>();

    const Eigen::MatrixXd B = Eigen::MatrixXd::NullaryExpr(
        80, 5, [](Eigen::Index i, Eigen::Index j) { return std::cos(double(3 * i + j)); });
    Eigen::MatrixXd x = B;
    solve_lower(dense_block(big.data(), 80, 80, 100), dense_block(x.data(), 80, 5, 80));
    EXPECT_LT((L * x - B).cwiseAbs().maxCoeff(), 1e-12);
    x = B;
    solve_lower_transposed(dense_block(big.data(), 80, 80, 100), dense_block(x.data(), 80, 5, 80));
    EXPECT_LT((L.transpose() * x - B).cwiseAbs().maxCoeff(), 1e-12);

    Eigen::MatrixXd C = Eigen::MatrixXd::Ones(5, 5);
    subtract_gram_lower(dense_block(C.data(), 5, 5, 5), dense_block(B.data(), 80, 5, 80));
    const Eigen::MatrixXd gram = Eigen::MatrixXd::Ones(5, 5) - B.transpose() * B;
    EXPECT_LT((C - gram).triangularView<Eigen::Lower>().toDenseMatrix().cwiseAbs().maxCoeff(),
              1e-12);
    EXPECT_EQ(C(0, 4), 1.0) << "the upper triangle is not written";

    Eigen::MatrixXd D = Eigen::MatrixXd::Ones(80, 5);
    subtract_product(dense_block(D.data(), 80, 5, 80), dense_block(A.data(), 80, 80, 80),
                     dense_block(B.data(), 80, 5, 80));
    EXPECT_LT((D - (Eigen::MatrixXd::Ones(80, 5) - A * B)).cwiseAbs().maxCoeff(), 1e-12);
    Eigen::MatrixXd E = Eigen::MatrixXd::Ones(5, 5);
    subtract_transposed_product(dense_block(E.data(), 5, 5, 5), dense_block(B.data(), 80, 5, 80),
                                dense_block(B.data(), 80, 5, 80));
    EXPECT_LT((E - gram).cwiseAbs().maxCoeff(), 1e-12);
}

} // namespace meshmorph::detail
