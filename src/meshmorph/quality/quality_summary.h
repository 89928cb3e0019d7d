// SPDX-License-Identifier: GPL-3.0-or-later
//! \file morphMesh's before/after table of the main quality numbers, read from the reports
//! themselves (typed fields and statistics), so that it prints what the checks found.
#pragma once

#include <iosfwd>

#include "meshmorph/quality/quality_report.h"

namespace meshmorph
{

//! \brief Print a compact before/after table of the main metrics, e.g.
//! ```
//!     metric                         before          after
//!     max non-orthogonality [deg]    12.5            31.2
//!     ...
//!     failed checks                  0               1
//! ```
//! Either side may be null (only one column then); a metric neither report has is left
//! out, one that only one has shows "-" on the other side. Reals with `precision`
//! significant digits; a non-finite value prints "-".
void print_quality_summary(std::ostream& out, const QualityReport* before,
                           const QualityReport* after, int precision = 6);

} // namespace meshmorph
