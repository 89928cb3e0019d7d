// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The largest valid step along a search direction, for an optimiser's line search. A
//! variant is linear in its amplitudes, so along a + t p every point moves on a straight
//! line and every face pyramid's volume is close to a cubic in t (quality/inversion_step.h):
//! its first root estimates where the first cell inverts. The search checks the estimate
//! with the variant check itself (DesignStudy::is_valid: no more negative-volume cells or
//! wrongly oriented face pyramids than the set-up's mesh), estimates again from each valid
//! estimate (closer each time: the cubic is exact at its start), and bisects the bracket
//! around the crossing.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "meshmorph/design/design_variant.h"

namespace meshmorph::design
{

//! What limited a step search, and how far it got.
struct ValidStep
{
    //! The largest step found valid: a + step p passes the variant check.
    double step = 0.0;
    //! The smallest step found invalid (+infinity when none was met: `step` is then the
    //! bound or the limit).
    double invalid_above = 0.0;
    //! The cubics' first estimate of the first inversion, from a (+infinity: none within the
    //! search).
    double estimate = 0.0;
    //! "inversion" (a cell inverts just above `step`), "bounds" (a variable reaches its
    //! bound at `step`; the variable is named in `bound_variable`), "limit" (the caller's) or
    //! "none" (no bound, no limit and nothing inverts: `step` is +infinity; finite only when
    //! the cubics foresaw an inversion the check did not find within 4^30 increments), or
    //! "nonOrthogonality" (checkMesh's maximum non-orthogonality passes the limit asked for
    //! by `invalid_above`).
    std::string limited_by;
    std::string bound_variable;
    //! With a non-orthogonality limit: checkMesh's maximum non-orthogonality at `step`
    //! [degrees] (NaN without one).
    double max_non_orthogonality = std::numeric_limits<double>::quiet_NaN();
    int checks = 0; //!< variant checks made
    double seconds = 0.0;
};

//! Relative width of the bracket [step, invalid_above] at which the search stops: steps a
//! line search tells apart are far coarser, and each halving costs one variant check.
inline constexpr double valid_step_tolerance = 1e-4;

//! \brief The largest t in [0, min(limit, bounds)] such that a + s p is valid for s = t
//! (confirmed by the check; the steps below it are not each checked).
//! \param max_non_orthogonality below 90 degrees: also keep checkMesh's maximum
//! non-orthogonality at or below it (the full check at 8 steps up to the valid step, then
//! bisection between the last step within it and the first beyond; it assumes the maximum
//! does not rise and fall back within an eighth of the step).
//! \throw InvalidInput for a direction of the wrong size, not finite or zero, a start that
//! is not valid or already above the non-orthogonality limit, or a limit that is not
//! positive. Collective with -parallel.
ValidStep largest_valid_step(DesignStudy& study, const std::vector<double>& a,
                             const std::vector<double>& direction, double limit,
                             double max_non_orthogonality = 90.0);

} // namespace meshmorph::design
