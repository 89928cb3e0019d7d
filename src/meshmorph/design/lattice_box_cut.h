// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Where a design lattice's box cuts the patches it moves, the motion must fade to zero
//! at the box, or the walls get a step there.
//!
//! The lattice is a uniform cubic B-spline whose box is its valid domain: its outer control
//! points sit one knot spacing outside the box (bspline_basis.h), and at a box face the motion
//! is (P0 + 4 P1 + P2) / 6 of the three outer layers there. With `confine c` those c layers are
//! held: c = 0 leaves the full motion at the face, 1 up to 5/6 of a control point's, 2 up to
//! 1/6, and only 3 zero with zero slope and curvature. The points of the patches just outside
//! the box do not move at all, so with fewer than 3 a patch that crosses the face gets a step,
//! and the cells beside it take the shear: OpenFOAM's sbend with its walls moved by a
//! 9 x 5 lattice, `confine (2 0 0)`, had its most skewed cells (0.97, 0.36 unmoved) at the
//! box's face after ten optimisation cycles.
#pragma once

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/design/design_variables.h"
#include "meshmorph/design/variable_constraints.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::design
{

//! A warning per lattice and axis whose box faces cut the lattice's patches (points of them
//! on both sides of the box along that axis) while `confine` holds fewer than 3 layers there:
//! how large the step can be, and that `confine 3` on that axis removes it. Collective.
void warn_lattice_box_cuts(const PolyMesh& mesh, const DesignVariables& variables,
                           const VariableConstraints& constraints,
                           const parallel::Communicator& comm);

} // namespace meshmorph::design
