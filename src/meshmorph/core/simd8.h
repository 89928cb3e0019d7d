// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: eight doubles as one value (GCC vector extension), for the loops that
//! are written lane by lane in the scalar code's order: the per-face kernels of the mesh
//! and quality components (mesh/foam_vector8.h) and the triharmonic RBF sum
//! (deform/rbf_evaluator.cpp).
//!
//! One AVX-512 register, or four SSE ones (GCC splits it). Without AVX-512 GCC notes
//! (-Wpsabi) that such a vector is passed and returned differently than with it; the
//! components including this header build with -Wno-psabi under GCC, as every object of a
//! build has the same flags and these functions are inline.
#pragma once

#include <cmath>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace meshmorph::detail
{

using double8 = double __attribute__((vector_size(64)));
//! The bits of eight doubles (logical shifts: the operands here are non-negative).
using bits8 = unsigned long long __attribute__((vector_size(64)));
inline constexpr int lanes8 = 8;

//! Eight consecutive doubles from p (no alignment needed), and back.
inline double8 load8(const double* p)
{
    double8 v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
}
inline void store8(double* p, const double8& v)
{
    __builtin_memcpy(p, &v, sizeof v);
}

//! Lane-wise square root (correctly rounded, as std::sqrt).
inline double8 sqrt8(const double8& v)
{
#if defined(__AVX512F__)
    // The zero-masked form: GCC 12 warns (-Wmaybe-uninitialized) about the unmasked one's
    // undefined pass-through operand where it inlines it into some loops.
    return reinterpret_cast<double8>(_mm512_maskz_sqrt_pd(0xFF, reinterpret_cast<__m512d>(v)));
#else
    double8 r;
    for (int l = 0; l < lanes8; ++l)
        r[l] = std::sqrt(v[l]);
    return r;
#endif
}

//! 1 / sqrt(x) lane-wise for finite x > 0, by Newton steps from the bit pattern that halves
//! the exponent (Lomont's constant for double): four steps take the relative error from
//! below 3.5e-2 through 1.7e-3, 4.5e-6 and 3e-11 to rounding (a few units in the last
//! place). IEEE multiplications and additions only, so for one build the bits do not depend
//! on the processor; an estimate instruction (rsqrt14) has the processor's own bits, its
//! error bound alone being specified. x = 0 gives a large finite value, not infinity.
inline double8 inverse_sqrt8(const double8& x)
{
    double8 y =
        reinterpret_cast<double8>(0x5fe6eb50c7b537a9ULL - (reinterpret_cast<bits8>(x) >> 1));
    const double8 h = 0.5 * x;
    for (int step = 0; step < 4; ++step)
        y = y * (1.5 - h * y * y);
    return y;
}

} // namespace meshmorph::detail
