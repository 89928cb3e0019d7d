// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The settings of the greedy RBF deformation (greedy_rbf_deformation.h): tolerances,
//! centre budget, batches and jump constraints. A plain record of its own, so that the
//! centre selection (greedy_centres.h) reads it without the deformation class.
#pragma once

#include "meshmorph/core/types.h"
#include "meshmorph/deform/rbf_settings.h"

namespace meshmorph
{

//! The settings of GreedyRbfDeformation.
struct GreedySettings
{
    RbfSettings rbf; //!< kernel, polynomial, tolerances of the underlying RBF
    //! Centres before the first refinement: the polynomial-unisolvent set plus farthest-point
    //! samples. 0: automatic, max(polynomial terms, min(20, constraints)).
    Index initial_centres = 0;
    //! Stop when max_i |d(x_i) - dx_i| <= tolerance * max_i |dx_i| ... The default is a
    //! coarse global field: morphMesh makes it exact with a local correction of the
    //! residual (CorrectedDeformation), which is cheaper and more robust near sharp features
    //! (a tyre on the ground) than thousands of global centres.
    double tolerance = 1e-2;
    //! ... and the RMS error <= rms_tolerance * max_i |dx_i| (equal to tolerance: implied).
    double rms_tolerance = 1e-2;
    //! Centre budget: stop (not converged) when reached.
    Index max_centres = 2000;
    //! Centres added per round (the worst points). 0: automatic, half as many as there are
    //! centres, at most 4096 (the count grows by 1.5 a round: the number of rounds grows like
    //! log(centres), and the last round overshoots the centres needed by at most 1.5x).
    Index batch_size = 0;
    //! Spread batches (0: off, the plain largest residuals): a round takes the constraints
    //! whose residual is above the tolerance, by the octave of their residual (largest
    //! first), then farthest from the centres first, skipping one that lies closer to one
    //! already taken than spread times its distance to the nearest centre. A batch so covers
    //! every region with a large residual instead of crowding the worst one (crowded batches
    //! make the interpolant ring where centres are sparse), and its choice does not follow
    //! the round-off of the residuals. A round whose RMS residual grows no longer ends the
    //! refinement (early rounds of a spread batch often do, on their way to the tolerance).
    double spread = 1.0;
    //! Jump constraints (jump_slope 0: off): a constraint whose displacement differs from a
    //! neighbour's by more than the band's slope times their distance (a moving wall touching
    //! a fixed one, a tyre on the floor) is never a centre and the tolerances are met on the
    //! others: the near-discontinuity is left to the caller's local correction by
    //! construction. The band (detail::jump_band) is max|h| / jump_slope wide, but at least
    //! jump_width times the extent of the moving constraints.
    //! - jump_slope 2: where the motion is large, the gap between the two closes or opens by
    //!   more than twice its width (a steeper global field folds cells: at a 13.5% lift of
    //!   the motorBike a slope of 2.7 made a cell the untangling had to repair).
    //! - jump_width 0.025: a band bound to the motion alone narrows with it, and the global
    //!   field must resolve a sharper feature the smaller the motion: on the motorBike 1747
    //!   centres at a 5% lift, the 2000-centre budget unconverged at 2.5% and 1% (residual
    //!   0.029 and 0.054). With the floor the band is 0.0635 m on the motorBike (the moving
    //!   box's diagonal: 2.54 m) up to a 9% lift: 1395 centres at every such lift, and the
    //!   fit scales with the motion. A band of 0.034 m (1/75) ran out of budget on the finer
    //!   x2 mesh; 1/40 converges there (1588 centres). docs/morph-method.md gives the reasons.
    double jump_slope = 2.0;
    double jump_width = 0.025;
};

} // namespace meshmorph
