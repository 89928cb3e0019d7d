// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: the triharmonic kernel r^3 = r2^(3/2) on eight lanes, by the square-root
//! unit or by Newton steps on the multiply-add units (the blocked RBF sum uses both).
//!
//! The triharmonic sums are bound by the square-root unit: on the AMD EPYC (AVX-512) cores the
//! benchmarks run on, a square root of eight lanes issues every ~13 cycles, while the rest of
//! a term (the difference, the squared distance, the three multiply-adds into the sums)
//! needs ~7 on the multiply-add units. r3_by_newton() computes r^3 without the square-root
//! unit, from 1/r by Newton steps (core/simd8.h: IEEE multiplications and additions only,
//! so for one build its bits do not depend on the processor). It stays within 6.5e-16 of
//! r2 * sqrt(r2) relative (measured over r2 = 1e-300 ... 1e300), a few rounding errors.
#pragma once

#include "meshmorph/core/simd8.h"

namespace meshmorph::detail
{

//! r2^(3/2) by the square-root unit (correctly rounded square root).
inline double8 r3_by_sqrt(const double8& r2)
{
    return r2 * sqrt8(r2);
}

//! r2^(3/2) by Newton steps on 1/r (inverse_sqrt8); 0 for r2 = 0 (and for r2 below 1e-300,
//! where r^3 < 1e-450 is 0 in double anyway).
inline double8 r3_by_newton(const double8& r2)
{
    const double8 x = r2 < 1e-300 ? double8{} + 1e-300 : r2;
    return r2 * (r2 * inverse_sqrt8(x));
}

} // namespace meshmorph::detail
