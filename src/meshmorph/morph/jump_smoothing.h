// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Jump smoothing: where the prescription jumps (a moving patch meeting a fixed one, a
//! tyre above the fixed floor), the interior points of a band around the jump get a
//! harmonic displacement instead of the fitted field's.
//!
//! The global fit leaves such constraints to the exact local correction (GreedySettings'
//! jump constraints), and the correction, an inverse-distance interpolant, is dominated by
//! the nearest boundary: an interior point a millimetre above the floor and a centimetre
//! from the tyre moves almost with the tyre, so the whole shear sits in the one layer of
//! cells touching the floor. A Laplacian, as OpenFOAM's displacementLaplacian solves it,
//! spreads it over the cells in between. Here the Laplacian is solved on the band alone:
//! its free points take the harmonic displacement of the mesh's edge graph with the field as
//! it was on the band's border and at every constrained point (Dirichlet), so the morph
//! stays exact and changes nowhere else.
//!
//! Edge weights 1 / (|e| dist), dist the distance along the edges to the nearest moving
//! jump constraint (capped at the band's depth): OpenFOAM's inverseDistance diffusivity.
//! Cells next to the moving wall are stiff and move with it; cells far from it (next to the
//! fixed wall) take the shear. The band: the free points within the jump band's width
//! (deform/jump_detection.h, the greedy RBF's default slope and width) of a constraint on a
//! jump, along the edges. Uniform weights gave 68.7 degrees on the motorBike's 5% lift,
//! 1 / |e|^2 72.2, these 66.4 (they stiffen the small cells by the floor).
//!
//! On graded meshes the small cells by the fixed wall take the shear instead: on the
//! tutorials' morph sweep it raised the largest non-orthogonality about as often as it
//! lowered it (pitzDaily 8.3 -> 20.8 degrees). So the default, `jumpSmoothing auto`, keeps
//! it only where it is better (jump_smoothing_guard.h). The band's graph and system:
//! jump_band_graph.h; -parallel: jump_smoothing_parallel.h.
#pragma once

#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph::morph
{

//! morphDict `jumpSmoothing`: `no`, `yes` (always) or `auto` (the default: smoothed, and the
//! smoothing kept only where it lowers the band's largest non-orthogonality, see
//! jump_smoothing_guard.h).
enum class JumpSmoothingMode
{
    off,
    on,
    automatic
};

//! "no", "yes" or "auto", as the morphDict spells it.
std::string to_string(JumpSmoothingMode mode);

//! What the smoothing did (for the log and the JSON report).
//! The most points within reach of the jumps (over every rank) the smoothing takes on. The
//! smoothing is for a band: the motorBike's holds 3,350 points; a wall scaled against fixed
//! sides along its whole length (OpenFOAM's channel395DFSEM, 1.9M points) reaches most of
//! the mesh, whose band Laplacian took over 5 GB and ten minutes to factor. Above this the
//! step is not smoothed, and the log says so.
inline constexpr Index max_jump_reach_points = 200000;

struct JumpSmoothing
{
    Index jump_constraints = 0; //!< constraints on a jump (the band's seeds)
    Index band_points = 0;      //!< free points whose displacement was replaced (every rank)
    //! Not smoothed: more points within reach of the jumps than the cap (a count above it; 0: none)
    Index skipped_reach = 0;
    double width = 0.0; //!< the band's width (distance along the edges)
    double seconds = 0.0;
    std::vector<Index> band; //!< those points' labels (this rank's, in label order)
    Points fitted;           //!< their displacement before the smoothing (one row each)
};

//! \brief Replace the displacement of the free points within the jump band by the harmonic
//! one (see the file comment). \param x_eval the points where the field is evaluated (2D: on
//! the reference empty plane; the jumps are found there, as the fit finds them), \param
//! constrained sorted mesh point labels of every constrained point (prescribed and slip),
//! \param values their prescribed displacements (one row each), \param displacement nPoints
//! x 3, the fitted field: changed in place on the band's free points only. Nothing happens
//! where the prescription has no jump (the band of deform/jump_detection.h with the greedy
//! RBF's default slope and width).
//! \throw SolverError if the band's system cannot be factored (it cannot happen for a band
//! that touches a constrained point, which every band does).
//! \param max_reach the cap on the points within reach (default max_jump_reach_points).
JumpSmoothing smooth_jumps(const PolyMesh& mesh, const Points& x_eval,
                           const std::vector<Index>& constrained, const Points& values,
                           Points& displacement, Index max_reach = max_jump_reach_points);

//! \brief The transpose of smooth_jumps as a linear map of the displacement (the band and its
//! weights held, as they depend on the prescription's shape only): `weights` (dJ/dd per
//! point, nPoints x 3) after the smoothing becomes dJ/dd before it: the band's rows are
//! carried to the points their Laplacian reads (the band's border and the constrained
//! points) and zeroed. Same arguments as smooth_jumps. \throw as smooth_jumps.
void smooth_jumps_transpose(const PolyMesh& mesh, const Points& x_eval,
                            const std::vector<Index>& constrained, const Points& values,
                            Points& weights);

} // namespace meshmorph::morph
