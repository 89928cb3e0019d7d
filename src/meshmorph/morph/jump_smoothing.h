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
//! jump constraint: OpenFOAM's inverseDistance diffusivity. Cells next to the moving wall
//! are stiff and move with it; cells far from it (next to the fixed wall) take the shear.
//! The band: the free points within the jump band's width (deform/jump_detection.h, the
//! greedy RBF's default slope and width) of a constraint on a jump, along the edges.
//!
//! Measured on the motorBike (benchmarks/morph/motorbike_vs_movemesh.sh -keys
//! "jumpSmoothing yes;"), max non-orthogonality / faces above 70 degrees, with the bike's
//! prescription winning where the tyres touch the floor (the motion moveMesh makes):
//! lift 5% 66.4 / 0 (without: 72.0 / 8; moveMesh 70.3 / 1), 9% 76.4 / 32 (79.8 / 33;
//! moveMesh 78.6 / 20 and a wrongly oriented pyramid), 13.5% 80.8 / 65 (83.3 / 181;
//! moveMesh 82.2 / 65 and a pyramid). With the contacts held (conflicts fixed): 5% 78.1 / 8
//! (77.7 / 8), 13.5% 84.9 / 9 (84.7 / 111). 0.04 s for the 3,300 points of the 5% band.
//! Uniform weights gave 68.7 at 5%, 1 / |e|^2 72.2 (they stiffen the small cells by the
//! floor). Off by default: on the tutorials' morph sweep (scripts/openfoam/checkmesh_sweep.sh
//! -morph -morph-keys "jumpSmoothing yes;", the smallest wall patch scaled 1%) no verdict
//! changed, but of the 154 meshes with a band max non-orthogonality rose on 99 (pitzDaily
//! 8.3 -> 20.8 degrees) and fell on 37: the weights stiffen the cells by the moving wall
//! only, and on graded meshes the small cells by the fixed wall take the shear. Serial only.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph::morph
{

//! What the smoothing did (for the log and the JSON report).
struct JumpSmoothing
{
    Index jump_constraints = 0; //!< constraints on a jump (the band's seeds)
    Index band_points = 0;      //!< free points whose displacement was replaced
    double width = 0.0;         //!< the band's width (distance along the edges)
    double seconds = 0.0;
};

//! \brief Replace the displacement of the free points within the jump band by the harmonic
//! one (see the file comment). \param constrained sorted mesh point labels of every
//! constrained point (prescribed and slip), \param values their prescribed displacements
//! (one row each), \param displacement nPoints x 3, the fitted field: changed in place on
//! the band's free points only. Nothing happens where the prescription has no jump (the
//! band of deform/jump_detection.h with the greedy RBF's default slope and width).
//! \throw SolverError if the band's system cannot be factored (it cannot happen for a band
//! that touches a constrained point, which every band does).
JumpSmoothing smooth_jumps(const PolyMesh& mesh, const std::vector<Index>& constrained,
                           const Points& values, Points& displacement);

} // namespace meshmorph::morph
