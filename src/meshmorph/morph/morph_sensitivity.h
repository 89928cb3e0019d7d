// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The reverse pass of a morph of a case: dJ/dx at the mesh points to dJ/dH, the
//! derivative with respect to each constrained point's prescribed displacement (dJ/dXs for
//! a parameterisation of the user's own), for the one field of a morph in one step.
#pragma once

#include "meshmorph/morph/morph_stages.h"

namespace meshmorph::morph
{

//! \brief dJ/dH at every mesh point of in.foam.mesh (x0; zero where nothing is prescribed)
//! for the morph `result` of `in` and dJ/dx `dJdx` at the same points. The field is fitted
//! again as the morph fitted it and transposed with its choices held
//! (morph_points_transpose). Points the morph's repair moved are taken as following the
//! field (a warning says how many). With -parallel (`parts`) a collective: this rank's
//! points, every shared point with the same value on every rank.
//! \throw InvalidInput before a morph, for a morph in several steps or what
//! morph_points_transpose does not cover; SolverError.
Points morph_sensitivity(const MorphCase& in, const MorphResult& result, const Points& dJdx,
                         const Decomposition* parts = nullptr);

} // namespace meshmorph::morph
