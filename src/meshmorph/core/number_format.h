// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Numbers as OpenFOAM's Ostream writes them: C's %.{p}g (general format with p
//! significant digits, "1e-05" style exponents, no trailing zeros), locale-independent. The
//! one formatter for reports, logs and the ASCII writers.
#pragma once

#include <string>

namespace meshmorph
{

//! \brief Appends `value` with `precision` significant digits (%.{p}g) to `out`.
void append_scalar(std::string& out, double value, int precision);

//! \brief `value` with `precision` significant digits (%.{p}g).
std::string format_scalar(double value, int precision);

} // namespace meshmorph
