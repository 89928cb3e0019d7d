// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: the triharmonic kernel r^3 = r2^(3/2) on eight lanes, by the square-root
//! unit or by Newton steps on the multiply-add units (the blocked RBF sum uses both).
//!
//! The triharmonic sums are bound by the square-root unit: on the AVX-512 Zen 4 cores the
//! benchmarks run on, a square root of eight lanes issues every ~13 cycles, while the rest of
//! a term (the difference, the squared distance, the three multiply-adds into the sums)
//! needs ~7 on the multiply-add units. r3_by_newton() computes r^3 without the square-root
//! unit: 1/r from the bit pattern that halves the exponent (relative error below 3.5%), then
//! four Newton steps, each squaring the error (3.4e-2, 1.7e-3, 4.5e-6, 3e-11, then
//! rounding). It uses IEEE multiplications and additions only, so for one build its bits do
//! not depend on the processor (an estimate instruction such as rsqrt14 would: its bits are
//! the processor's). It stays within 6.5e-16 of r2 * sqrt(r2) relative (measured over
//! r2 = 1e-300 ... 1e300), a few rounding errors.
#pragma once

#include "meshmorph/core/simd8.h"

namespace meshmorph::detail
{

//! r2^(3/2) by the square-root unit (correctly rounded square root).
inline double8 r3_by_sqrt(const double8& r2)
{
    return r2 * sqrt8(r2);
}

//! r2^(3/2) by Newton steps on 1/r (see the file's comment); 0 for r2 = 0 (and for r2 below
//! 1e-300, where r^3 < 1e-450 is 0 in double anyway).
inline double8 r3_by_newton(const double8& r2)
{
    const double8 x = r2 < 1e-300 ? double8{} + 1e-300 : r2;
    // The exponent-halving guess for 1/sqrt(x) (Lomont's constant for double).
    double8 y =
        reinterpret_cast<double8>(0x5fe6eb50c7b537a9ULL - (reinterpret_cast<bits8>(x) >> 1));
    const double8 h = 0.5 * x;
    for (int step = 0; step < 4; ++step)
        y = y * (1.5 - h * y * y);
    return r2 * (r2 * y);
}

} // namespace meshmorph::detail
