// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The first step at which a cubic that is positive at zero stops being positive: the
//! volume of a tet whose corners move linearly, p(t) = c0 + c1 t + c2 t^2 + c3 t^3, reaches
//! zero (inversion_step.h builds such cubics for every face pyramid of a mesh).
#pragma once

#include <array>

namespace meshmorph
{

//! Coefficients c0..c3 of c0 + c1 t + c2 t^2 + c3 t^3.
using Cubic = std::array<double, 4>;

//! \brief The smallest t in (0, limit] with p(t) <= 0, to a relative 1e-13, found on the
//! cubic's monotone pieces (split at the roots of p') by a bracketing solver (Illinois), so
//! a root that a coarse sampling would step over is not missed. \param limit may be +infinity (the
//! roots then lie within Cauchy's bound). \pre p(0) = c0 > 0. \return +infinity if there is none.
double first_nonpositive_step(const Cubic& p, double limit);

//! p(t), by Horner's rule.
inline double evaluate_cubic(const Cubic& p, double t)
{
    return ((p[3] * t + p[2]) * t + p[1]) * t + p[0];
}

} // namespace meshmorph
