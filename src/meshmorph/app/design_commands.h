// SPDX-License-Identifier: GPL-3.0-or-later
//! \file morphMesh's design-study options: -variables (set up), -variant and -variants
//! (designs from the set-up), -sensitivity (dJ/da by the transpose product); their log,
//! JSON and exit status. The work is the design/ module's.
#pragma once

#include <filesystem>
#include <iosfwd>

#include <nlohmann/json.hpp>

#include "meshmorph/app/options.h"
#include "meshmorph/design/design_setup.h"
#include "meshmorph/design/design_variant.h"
#include "meshmorph/design/valid_step.h"
#include "meshmorph/morph/morph_result.h"

namespace meshmorph::app
{

//! `invalidCellsByPatch` of morphMesh's and a variant's report: {patch: cells}.
nlohmann::json invalid_cells_json(const std::vector<morph::PatchCells>& counts);

//! The JSON of -variables: exitStatus, setupFile, method, points, constrainedPoints,
//! variables [{name, movesPoints, maxConstraintError, relativeConstraintError, centres,
//! seconds}], bytes, seconds, before.
nlohmann::json setup_json(const design::DesignSetupResult& r);
//! The JSON of one variant: setupReused, setupFile, amplitudes {name: a}, valid, written,
//! outputInstance, path, maxPrescribedDisplacement, maxConstraintError,
//! relativeConstraintError, maxDisplacement, timings {combine, check, write}, after; when
//! the linear combination had new invalid cells untangle {invalidBefore, invalidAfter,
//! pointsMoved, maxMove, seconds} (or {skipped: why} when the damage was too wide to
//! repair locally); newFailedChecks, invalidCellsByPatch; when refused also refusal and
//! backOff.
nlohmann::json variant_json(const design::DesignStudy& study, const design::VariantResult& r);

//! The JSON of -variant A -direction P (a step search; no mesh written): setupReused,
//! setupFile, written (false), amplitudes and direction {name: value}, step, invalidAbove
//! and estimate (null: unbounded), limitedBy ("inversion", "bounds", "limit", "none" or
//! "nonOrthogonality"), maxNonOrthogonality at the step (null unless -maxNonOrtho),
//! boundVariable, checks, seconds.
nlohmann::json valid_step_json(const design::DesignStudy& study, const std::vector<double>& a,
                               const std::vector<double>& direction, const design::ValidStep& r);

//! Whether the command line asks for a design-study command.
bool is_design_command(const Options& options);

//! \brief Run the design command of the command line (exactly one of them).
//! \throw UsageError for two commands or an option that does not go with them; the library's
//! errors otherwise. \return the exit status (exit_refused when a variant is refused).
int run_design_command(const Options& options, const morph::MorphOptions& morph,
                       const std::filesystem::path& json_path, std::ostream& out);

} // namespace meshmorph::app
