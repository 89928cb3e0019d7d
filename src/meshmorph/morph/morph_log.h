// SPDX-License-Identifier: GPL-3.0-or-later
//! \file What a morph tells the user as it goes: the set-up per patch, the fit and the
//! field, and a mesh that was already broken.
#pragma once

#include <filesystem>

#include "meshmorph/morph/constraint_set.h"
#include "meshmorph/morph/deformation_methods.h"
#include "meshmorph/morph/morph_result.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::morph
{

//! A mesh that already fails checks (open cells, zero-area faces, ...) is morphed (only new
//! invalid cells refuse a morph), but the user hears that the result inherits the damage.
void warn_if_broken(const QualityReport& before, const std::filesystem::path& mesh_dir);

//! The set-up, as the user should see it: per patch its motion and why, the constraint
//! counts, conflicts and near agreements.
void log_setup(const Constraints& c);

//! The fit and the field, as the user should see them: centres, residuals, the largest
//! displacement against the largest prescribed one, the constraint error.
void log_fit(const MorphResult& result, const DeformationSettings& settings, Index n_points);

} // namespace meshmorph::morph
