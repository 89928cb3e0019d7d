// SPDX-License-Identifier: GPL-3.0-or-later
// The fits' dense linear algebra by Eigen on the calling thread (see the header for why).
#include "meshmorph/deform/dense_kernels.h"

#include <cmath>
#include <mutex>

#include <Eigen/Cholesky>

namespace meshmorph::detail
{

namespace
{

//! L L^T as a decomposition for Eigen's condition estimator (solve and adjoint().solve()).
struct CholeskyFactor
{
    using MatrixType = Eigen::MatrixXd;
    using Scalar = double;
    using RealScalar = double;

    const ConstDenseBlock& l;

    Eigen::Index rows() const { return l.rows(); }
    Eigen::Index cols() const { return l.cols(); }
    const CholeskyFactor& adjoint() const { return *this; }
    Eigen::VectorXd solve(const Eigen::VectorXd& b) const
    {
        Eigen::VectorXd x = b;
        l.triangularView<Eigen::Lower>().solveInPlace(x);
        l.transpose().triangularView<Eigen::Upper>().solveInPlace(x);
        return x;
    }
};

} // namespace

DenseMap dense_block(double* data, Eigen::Index rows, Eigen::Index cols, Eigen::Index leading)
{
    return {data, rows, cols, Eigen::OuterStride<>(leading)};
}

ConstDenseMap dense_block(const double* data, Eigen::Index rows, Eigen::Index cols,
                          Eigen::Index leading)
{
    return {data, rows, cols, Eigen::OuterStride<>(leading)};
}

void use_one_eigen_thread()
{
    static std::once_flag once;
    std::call_once(once, [] { Eigen::setNbThreads(1); });
}

Eigen::Index cholesky_lower(DenseBlock a)
{
    use_one_eigen_thread();
    Eigen::Index failed = Eigen::internal::llt_inplace<double, Eigen::Lower>::blocked(a);
    // Eigen stops at a pivot <= 0; a NaN pivot passes that test (dpotrf stops there too).
    const Eigen::Index done = failed < 0 ? a.rows() : failed;
    for (Eigen::Index k = 0; k < done; ++k)
        if (!std::isfinite(a(k, k)))
            return k;
    return failed;
}

double symmetric_norm1(const ConstDenseBlock& a)
{
    double norm = 0.0;
    for (Eigen::Index j = 0; j < a.cols(); ++j)
    {
        const double column =
            a.col(j).tail(a.rows() - j).lpNorm<1>() + a.row(j).head(j).lpNorm<1>();
        norm = std::max(norm, column);
    }
    return norm;
}

double cholesky_reciprocal_condition(const ConstDenseBlock& l, double norm)
{
    use_one_eigen_thread();
    return Eigen::internal::rcond_estimate_helper(norm, CholeskyFactor{l});
}

void subtract_gram_lower(DenseBlock c, const ConstDenseBlock& a)
{
    use_one_eigen_thread();
    c.selfadjointView<Eigen::Lower>().rankUpdate(a.transpose(), -1.0);
}

void solve_lower(const ConstDenseBlock& l, DenseBlock x)
{
    use_one_eigen_thread();
    l.triangularView<Eigen::Lower>().solveInPlace(x);
}

void solve_lower_transposed(const ConstDenseBlock& l, DenseBlock x)
{
    use_one_eigen_thread();
    l.transpose().triangularView<Eigen::Upper>().solveInPlace(x);
}

void subtract_product(DenseBlock c, const ConstDenseBlock& a, const ConstDenseBlock& b)
{
    use_one_eigen_thread();
    c.noalias() -= a * b;
}

void subtract_transposed_product(DenseBlock c, const ConstDenseBlock& a, const ConstDenseBlock& b)
{
    use_one_eigen_thread();
    c.noalias() -= a.transpose() * b;
}

} // namespace meshmorph::detail
