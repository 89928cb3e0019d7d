// SPDX-License-Identifier: GPL-3.0-or-later
//! \file checkMesh's report text from a QualityReport: one formatter per check, looked up
//! in a table by the result's id, walking the list of check results in order.
#pragma once

#include <string>

#include "meshmorph/quality/check_settings.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph
{

//! \brief The text checkMesh prints, from "Mesh stats" to "Mesh OK." / "Failed N mesh
//! checks.". \param settings what was checked (the options) and how to print (precision,
//! set lines, meshQuality thresholds).
//! \throw std::logic_error for a check result the report has no formatter for.
std::string report_text(const QualityReport& report, const CheckMeshSettings& settings);

} // namespace meshmorph
