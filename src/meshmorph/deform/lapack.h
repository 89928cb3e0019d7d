// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Declarations of the two Fortran BLAS/LAPACK routines deform uses: DM-FFD's SVD and
//! the handle basis's product (OpenBLAS provides them; Debian ships no LAPACKE/CBLAS headers
//! by default, so we declare the symbols). The RBF fits use none (dense_kernels.h).
#pragma once

extern "C"
{
    void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                const double* alpha, const double* a, const int* lda, const double* b,
                const int* ldb, const double* beta, double* c, const int* ldc);
    void dgesdd_(const char* jobz, const int* m, const int* n, double* a, const int* lda, double* s,
                 double* u, const int* ldu, double* vt, const int* ldvt, double* work,
                 const int* lwork, int* iwork, int* info);
}

namespace meshmorph::detail
{

//! Makes OpenBLAS's pthread build single-threaded (once per process), so that DM-FFD's SVD
//! gives the same bits whatever OMP_NUM_THREADS or OPENBLAS_NUM_THREADS say. A no-op with another
//! BLAS, and with OpenBLAS's OpenMP build (its thread count is OpenMP's: there the fits agree
//! across thread counts to round-off, docs/same-result.md).
void use_one_blas_thread();

//! Checked narrowing of a matrix dimension to LAPACK's 32-bit int. Every BLAS/LAPACK call
//! of deform passes its dimensions through here, so this is also where the BLAS is made
//! single-threaded (use_one_blas_thread) before its first use.
int lapack_int(long long n);

} // namespace meshmorph::detail
