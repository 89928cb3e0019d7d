// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A whole morph of an OpenFOAM case as one library call: read the case and its
//! morphDict, build the constraints, check the mesh, fit and evaluate in steps, check again,
//! refuse or write (morph_case). morphMesh is this call plus its options and report.
//!
//! Decisions (documented for users in `morphMesh -help`, docs/morphMesh.md and docs/morphDict.md):
//! - Exactness: rbf and idw interpolate every constraint (point_morph.h); nothing is
//!   snapped after the evaluation.
//! - Steps: the motion is applied in refitted fractions, halved on new invalid cells
//!   (morph_steps.h).
//! - Safety. A morph that creates negative-volume cells or wrongly oriented face pyramids
//!   (more than before) is refused: nothing is written unless `force`.
#pragma once

#include "meshmorph/morph/morph_result.h"

namespace meshmorph::morph
{

//! \brief Run the whole morph in a case directory (see morphMesh -help).
//! Dictionary, mesh and surface errors throw before anything is written.
//! \throw ParseError, IoError, InvalidInput, SolverError.
MorphResult morph_case(const MorphOptions& options);

} // namespace meshmorph::morph
