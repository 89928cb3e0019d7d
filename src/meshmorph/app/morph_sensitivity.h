// SPDX-License-Identifier: GPL-3.0-or-later
//! \file `morphMesh -sensitivity FILE` on a case whose morphDict declares no design
//! variables: dJ/dXs, the sensitivity with respect to the prescribed boundary displacements
//! of the morphDict's morph (the reverse pass of its field, MorphSession::sensitivity), for
//! a user with a parameterisation of their own (CAD, an FFD of pyGeo's, OpenFOAM's
//! volumetric B-splines) to chain, as IDWarp's warpDeriv serves.
#pragma once

#include <filesystem>
#include <iosfwd>

#include "meshmorph/morph/morph_result.h"

namespace meshmorph::app
{

//! Whether options' morphDict has a `designVariables` dictionary (then -sensitivity gives
//! dJ/da of those variables instead).
bool declares_design_variables(const morph::MorphOptions& options);

//! \brief Morph with the morphDict in memory, read dJ/dx from `file` (a pointVectorField,
//! relative to the case), and write dJ/dXs beside it as the pointVectorField `dJdXs`
//! (nonzero at the constrained points; OpenFOAM reads it back); JSON to `json_path` if
//! given. \return the exit status. \throw InvalidInput (-parallel, a morph in several steps
//! or untangled, what the reverse pass does not cover), ParseError, IoError.
int run_morph_sensitivity(const morph::MorphOptions& options, const std::filesystem::path& file,
                          const std::filesystem::path& json_path, std::ostream& out);

} // namespace meshmorph::app
