// SPDX-License-Identifier: GPL-3.0-or-later
//! \file build_constraints for a -parallel run: every rank collects the claims of its part,
//! the master resolves them once for the whole mesh and sends each rank the prescriptions of
//! its points.
//!
//! The claims (a few per boundary point) travel once to the master, never to every rank.
//! Points are identified by their label in the undecomposed mesh, so the master resolves
//! exactly the claims a serial run resolves, in the same order: the constraints are those of
//! the serial run, split by rank (a point shared by ranks gets the same prescription on
//! each). Counts and the conflict summary are complete on the master only.
#pragma once

#include "meshmorph/morph/claims.h"
#include "meshmorph/morph/constraint_set.h"
#include "meshmorph/morph/decomposition.h"

namespace meshmorph::morph
{

//! \pre decomposition.is_distributed(). A collective: call on every rank. \throw as
//! build_constraints, on every rank.
Constraints build_distributed_constraints(const PolyMesh& mesh, const MorphSetup& setup,
                                          const ConstraintInputs& inputs,
                                          const Decomposition& decomposition);

} // namespace meshmorph::morph
