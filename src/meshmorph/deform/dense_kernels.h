// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: the dense linear algebra of the RBF fits (Cholesky, triangular solves,
//! Gram and general products), by Eigen on the calling thread.
//!
//! Why not BLAS/LAPACK: OpenBLAS picks its kernels at run time by processor (or by
//! OPENBLAS_CORETYPE), and their last bits differ. The fits amplify them by their condition
//! number (1e10 for the greedy RBF on the motorBike: 1e-6 of the motion), and a borderline
//! repair or verdict then depends on the processor's kernel (the bent venturi's repair
//! succeeded under 9 of 13 kernels). Eigen's kernels are compiled into meshMorph, so one
//! build gives the same bits on every processor whatever OpenBLAS is installed.
//!
//! Why one thread: Eigen splits a product's blocks by its thread count, and the bits follow.
//! The callers parallelise over independent columns themselves, in blocks that do not depend
//! on the thread count (RowPanelFactor::forward).
#pragma once

#include <Eigen/Core>

namespace meshmorph::detail
{

//! A column-major block of a larger array (leading dimension >= rows), in and out.
using DenseBlock = Eigen::Ref<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using ConstDenseBlock = Eigen::Ref<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using DenseMap = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
using ConstDenseMap = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;

//! rows x cols at data, leading dimension `leading`.
DenseMap dense_block(double* data, Eigen::Index rows, Eigen::Index cols, Eigen::Index leading);
ConstDenseMap dense_block(const double* data, Eigen::Index rows, Eigen::Index cols,
                          Eigen::Index leading);

//! Makes Eigen's own products single-threaded (once per process): see the file comment.
void use_one_eigen_thread();

//! A := L with L L^T = A, from and into A's lower triangle (the upper part is not read).
//! \return -1, or the first column whose pivot is not positive or not finite (A's leading
//! block before it then holds its factor), as LAPACK's dpotrf's info - 1.
Eigen::Index cholesky_lower(DenseBlock a);

//! The reciprocal condition number (1-norm) of the symmetric positive definite matrix whose
//! lower triangle had the 1-norm `norm` (symmetric_norm1, taken before cholesky_lower) and
//! whose factor L is given: Hager and Higham's estimate, as LAPACK's dpocon.
double cholesky_reciprocal_condition(const ConstDenseBlock& l, double norm);
//! The 1-norm of the symmetric matrix whose lower triangle is given (LAPACK's dlansy "1").
double symmetric_norm1(const ConstDenseBlock& a);

//! C := C - A^T A on C's lower triangle (BLAS dsyrk "L", "T" with alpha -1, beta 1).
void subtract_gram_lower(DenseBlock c, const ConstDenseBlock& a);

//! X := L^-1 X, L lower triangular (its upper part is not read).
void solve_lower(const ConstDenseBlock& l, DenseBlock x);
//! X := L^-T X, L lower triangular (its upper part is not read).
void solve_lower_transposed(const ConstDenseBlock& l, DenseBlock x);

//! C := C - A B.
void subtract_product(DenseBlock c, const ConstDenseBlock& a, const ConstDenseBlock& b);
//! C := C - A^T B.
void subtract_transposed_product(DenseBlock c, const ConstDenseBlock& a, const ConstDenseBlock& b);

} // namespace meshmorph::detail
