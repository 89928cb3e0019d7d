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

} // namespace meshmorph::detail
