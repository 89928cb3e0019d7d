// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Near-discontinuities of scattered data: the points whose value changes faster than
//! a given slope towards some neighbour (a moving wall touching a fixed one: a tyre on the
//! floor). A smooth global interpolant rings around such points; the greedy RBF leaves them
//! to the local correction.
#pragma once

#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph::detail
{

//! Flags (1/0, one per row of x) of the points i with some j such that
//! |v_i - v_j| > slope |x_i - x_j| and |x_i - x_j| <= reach; the number of flagged points
//! in `count`. Exact (every pair within reach that could qualify is tested); the two
//! comparisons are made on coarsened values (tie_break.h), so a pair on the boundary of the
//! definition is decided alike on every processor. Cells of reach/2
//! are compared first as a whole: a pair of cells whose values differ by at most slope
//! times the cells' distance holds no such pair and is skipped, so data that is constant
//! over large regions (a translated body, fixed walls) costs little beyond the cells where
//! different values meet. OpenMP over cells; the result does not depend on the threads.
std::vector<char> jump_points(const Points& x, const Eigen::MatrixXd& values, double slope,
                              double reach, Index& count);

//! The near-discontinuities a fit leaves out: pairs whose values differ by more than `slope`
//! times their distance, which can only be closer than `width` apart (values differ by at
//! most twice the largest, so a pair spans at most 2 width).
struct JumpBand
{
    double slope = 0.0;  //!< 0: no band (jumps off, or all values zero)
    double width = 0.0;  //!< max |v| / slope
    double extent = 0.0; //!< the diagonal of the moving points' bounding box
};

//! The band for values v at x: max|v| / max_slope wide, but at least min_width times the
//! extent of the moving points (those whose |v| exceeds 1e-6 of the largest, so that the
//! round-off of a rotation about an axis through a patch is no motion). A band bound to the
//! motion alone narrows with it: the smaller the motion, the sharper the feature a smooth
//! fit must resolve (on the motorBike a 1% lift ran a greedy RBF into its 2000-centre
//! budget). Where min_width sets it, the band, and with it the pairs left out, stay the same
//! when the values are scaled: the fit is linear in the amplitude of the motion. max_slope 0
//! (or all values 0): no band; min_width 0: max_slope alone.
JumpBand jump_band(const Points& x, const Eigen::MatrixXd& values, double max_slope,
                   double min_width);

//! The constraints on a jump as a fit leaves them out: jump_points with the slope of
//! jump_band(x, values, max_slope, min_width). Pairs farther apart than twice the band's
//! width cannot jump; nor are pairs farther apart than 1/20 of the points' extent looked at
//! (a change over such a distance is no near-discontinuity). \return the flags (empty when
//! there is no band or fewer than two points); the band in `band`, the count in `count`.
std::vector<char> jump_constraints(const Points& x, const Eigen::MatrixXd& values, double max_slope,
                                   double min_width, JumpBand& band, Index& count);

} // namespace meshmorph::detail
