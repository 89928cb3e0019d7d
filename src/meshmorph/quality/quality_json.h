// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The checker's machine-readable report (JSON) and a compact before/after summary.
//!
//! The JSON object is an interface shared with morphMesh (which embeds it as `before` and
//! `after`); its key names are fixed: points, faces, internalFaces, cells, patches,
//! cellTypes{hexahedra, prisms, wedges, pyramids, tetWedges, tetrahedra, polyhedra},
//! boundingBox [[min],[max]], maxCellOpenness, maxAspectRatio, minFaceArea, maxFaceArea,
//! minVolume, maxVolume, totalVolume, negativeVolumeCells, maxNonOrthogonality,
//! avgNonOrthogonality, severelyNonOrthogonalFaces (> 70 deg), nonOrthogonalityErrors
//! (> 90 deg), incorrectlyOrientedFacePyramids, maxSkewness, highlySkewedFaces,
//! failedChecks, meshOK, minScaledJacobian (null when not computed); with -allGeometry also
//! minFaceWeight, minVolumeRatio, smallDeterminantCells, concaveCells, warpedFaces,
//! faceTetErrors (and a few more); with -meshQuality `meshQualityFailures` {criterion: count}.
#pragma once

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshmorph/quality/quality_report.h"

namespace meshmorph
{

//! \brief The JSON object of a report (see the file comment for the keys). Non-finite
//! numbers (e.g. an undefined scaled Jacobian) become null.
nlohmann::json quality_json(const QualityReport& report);

//! `newFailedChecks` of morphMesh's report: [{check, count}] per (check name, offenders).
nlohmann::json failed_checks_json(const std::vector<std::pair<std::string, Index>>& failures);

} // namespace meshmorph
