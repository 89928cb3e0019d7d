// SPDX-License-Identifier: GPL-3.0-or-later
//! \file One checkMesh report from every rank's part of a decomposed mesh (checkMesh
//! -parallel): the numbers combined on the master, the text as checkMesh -parallel prints it.
#pragma once

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/processor_faces.h"
#include "meshmorph/quality/check_settings.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph
{

//! \brief The report of the whole mesh on the master (`local` on the other ranks), from each
//! rank's check_mesh(..., &processors). A collective.
//!
//! The text prints what checkMesh -parallel prints: the ranks' point and face counts summed,
//! "boundary patches: N (min max)", and "basic patch addressing" tables (sizes and bounding
//! boxes, no surface topology). The numbers (and the JSON) are those of the undecomposed
//! mesh, equal to a serial check of the reconstructed mesh: shared points and processor
//! faces count once, processor faces are internal faces.
//! \param global_points the undecomposed mesh's number of points (pointProcAddressing).
QualityReport reduce_report(const QualityReport& local, const PolyMesh& mesh,
                            const CheckMeshSettings& settings, const ProcessorFaces& processors,
                            Index global_points);

} // namespace meshmorph
