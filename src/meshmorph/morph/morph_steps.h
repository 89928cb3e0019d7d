// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Large motions in steps, guided by the checker (morphDict `steps N | auto`).
//!
//! The prescribed motion is applied in fractions t_1 < t_2 < ... < 1 of itself: at each
//! step the deformation is refitted on the mesh moved so far, to the displacements that
//! take the constrained points from where they are to where fraction t_k puts them
//! (rotations turn by t_k times their angle, every other prescription moves t_k of its
//! displacement along a straight line). Slip points are re-derived at every step.
//!
//! A step whose result has more negative-volume cells or wrongly oriented face pyramids
//! than the original mesh is first repaired in place by local untangling (morph/
//! local_untangle.h: interior points near the new invalid cells move, boundary points
//! never do; morphDict `untangle no` turns it off). `steps auto` (the default) starts with
//! one step. A step still invalid after the repair is redone at half its length, down to
//! 1/max_steps of the motion; the shorter length is kept for the rest. If even the shortest step
//! fails, the rest of the motion is applied in one step and the result is refused (written with
//! -force: the whole motion, never a part of it). `steps N` makes N equal steps and never redoes
//! one.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "meshmorph/morph/jump_smoothing_guard.h"
#include "meshmorph/morph/local_untangle.h"
#include "meshmorph/morph/non_ortho_repair.h"
#include "meshmorph/morph/point_morph.h"
#include "meshmorph/quality/cell_validity.h"

namespace meshmorph::io
{
class FoamDictionary;
}

namespace meshmorph::morph
{

struct StepSettings
{
    int steps = 0;        //!< 0: auto; N >= 1: N equal steps
    int max_steps = 64;   //!< auto: the shortest step is 1/max_steps of the motion
    bool untangle = true; //!< repair a step's new invalid cells before judging it
    //! morphDict `maxUntangleCells`: a step with more cells to repair is not repaired (it
    //! is halved, or refused). The repair is for a few cells: it costs about 10 ms per
    //! cell, and on the channel395DFSEM tutorial no repair of more than ~200 cells (from
    //! 30,800 down to 784) made its step valid, in 774 s in all.
    Index max_untangle_cells = 1000;
    //! morphDict `maxNonOrtho` (degrees; 0: `none`): a valid step's cells with a face it took
    //! above this are repaired locally (non_ortho_repair.h), with `untangle`.
    double max_non_ortho = 70.0;
};

//! \brief Read `steps auto;` or `steps N;` (absent: auto), `untangle yes|no;` (absent:
//! yes), `maxUntangleCells N;` (absent: 1000) and `maxNonOrtho D | none;` (absent: 70).
//! \throw ParseError.
StepSettings read_step_settings(const io::FoamDictionary& dict);

//! What one step (tried or kept) did.
struct StepRecord
{
    double from = 0.0, to = 1.0; //!< fractions of the motion
    Index centres = 0;
    //! Relative residual the local correction took up, over the constraints the global part
    //! fits (all but the jump constraints, which the correction takes up alone).
    double max_global_residual = 0.0;
    Index jump_constraints = 0;
    Index jump_smoothed_points = 0;  //!< free points the jump smoothing set (jump_smoothing.h)
    JumpSmoothingChoice jump_choice; //!< `jumpSmoothing auto`: what was compared and kept
    double fit_seconds = 0.0, evaluate_seconds = 0.0, check_seconds = 0.0;
    InvalidCells invalid;    //!< after the repair, if there was one
    UntangleReport untangle; //!< the repair (invalid_before 0: none was needed)
    double untangle_seconds = 0.0;
    NonOrthoRepair non_ortho; //!< the repair of faces above maxNonOrtho (cells 0: none needed)
    bool accepted = false;
};

struct SteppedMorph
{
    Points points;                    //!< nPoints x 3, the morphed points
    Points displacement;              //!< points - original points
    std::vector<StepRecord> steps;    //!< every step tried, in order
    PointMorph last;                  //!< the last step's fit (counts, report)
    MeshGeometry geometry;            //!< of the final points (for the final check)
    std::vector<char> pyramid_errors; //!< face_pyramid_errors of the final points (same)
    //! The fraction of the motion reached without new invalid cells (1: all of it). The
    //! whole motion is always applied: with auto, once even the shortest step fails the
    //! rest goes in one step, so that -force writes the motion asked for.
    double valid_fraction = 1.0;
};

//! Builds a fresh deformation for a step, given the corners of the current points' bounding
//! box (2 x 3; over every rank in a -parallel run).
using DeformationMaker = std::function<std::unique_ptr<SpaceDeformation>(const Points&)>;

//! \brief Displacements of the constrained points (rows of c.points) from x0 at fraction t.
Points prescribed_at(const Constraints& c, const Points& x0, double t);

//! \brief Set m.max_prescribed and the constraint errors of m.displacement (from the
//! original points x0) against the whole prescribed motion of c.
void measure_constraint_error(const Constraints& c, const Points& x0, PointMorph& m,
                              const Decomposition* decomposition = nullptr);

//! \brief Morph `mesh` in steps. \param fit false: one step with the deformation as made
//! (FFD). \param before the original mesh's invalid counts (over every rank), asked for
//! when the first step is judged (the check before may still be running until then).
//! \param in_place null, or `mesh` itself given mutable (a single morph of a case): its
//! points are the working state during the call (the original ones kept aside: no copy
//! of the mesh) and the original ones again at return. \throw as morph_points(); then
//! an in-place `mesh` may be left with a step's points.
//! \param decomposition -parallel: this rank's part (every decision is global: counts are
//! summed over the ranks, the master fits). \throw as morph_points().
SteppedMorph morph_in_steps(const PolyMesh& mesh, const CompactList& cell_faces,
                            const Constraints& c, const StepSettings& settings,
                            const DeformationMaker& make, bool fit,
                            const std::function<InvalidCells()>& before,
                            const Decomposition* decomposition = nullptr,
                            PolyMesh* in_place = nullptr);

//! "auto" or the number.
std::string describe(const StepSettings& settings);

} // namespace meshmorph::morph
