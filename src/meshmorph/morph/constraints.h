// SPDX-License-Identifier: GPL-3.0-or-later
//! \file morphDict boundary and handle prescriptions, resolved into point constraints.
//!
//! build_constraints() composes the steps: the patches' entries (patch_assignment.h), the
//! empty planes of 2D cases (empty_planes.h), the claims of every boundary point
//! (claims.h), one prescription per point (conflict_resolution.h), the handles' claims
//! (handle_selection.h) resolved by the same rule, and the merge: handles override boundary
//! prescriptions, since they are the explicit, local request (the number of overridden
//! boundary points is reported). A dictionary that asks for motion but resolves to none is
//! an error. The rules are documented for users in docs/morphDict.md and `morphMesh -help`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/types.h"
#include "meshmorph/morph/claims.h"
#include "meshmorph/morph/constraint_set.h"
#include "meshmorph/morph/morph_setup.h"

namespace meshmorph::morph
{

//! Resolve boundary and handle prescriptions into point constraints.
//! \throw ParseError/InvalidInput on dictionary errors (unknown patch/zone, conflicts under
//! rule `error`, non-planar slip patch, missing inputs for data-driven types, motion asked
//! for but none left).
Constraints build_constraints(const PolyMesh& mesh, const MorphSetup& setup,
                              const ConstraintInputs& inputs = {});

} // namespace meshmorph::morph
