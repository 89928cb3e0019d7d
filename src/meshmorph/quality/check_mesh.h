// SPDX-License-Identifier: GPL-3.0-or-later
//! \file checkMesh-equivalent mesh checks and their report (docs/checkmesh-spec.md).
//!
//! check_mesh() runs OpenFOAM v1912 checkMesh's topology (§3.2), geometry (§3.3),
//! -allGeometry (§3.4) and -meshQuality (§5) checks on an in-memory PolyMesh and returns
//! both the report text checkMesh would print (from "Mesh stats" to "Mesh OK." /
//! "Failed N mesh checks.") and every number, offending face/cell/point set and per-cell
//! field, so that applications can write sets, VTK fields and JSON.
//!
//! It is the driver of three tiers (as OpenFOAM's primitiveMeshTools -> primitiveMesh::check*
//! -> checkGeometry.C): metric functions (face_orthogonality.h, face_skewness.h, ...) return
//! per-face and per-cell fields; check functions (topology_checks.h, geometry_checks.h,
//! mesh_quality_checks.h) turn them into CheckResults; report_text.h and quality_json.h walk
//! the results. A caller that needs a few checks only calls those (see cell_validity.h).
#pragma once

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/mesh/processor_faces.h"
#include "meshmorph/quality/check_settings.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph
{

//! \brief Run checkMesh's checks (spec §3, §5) and build the report.
//! \param mesh a mesh with valid addressing (face vertex labels in [0, nPoints), owner and
//!        neighbour in [0, nCells)); the topology checks report everything else.
//! \param geometry compute_geometry(mesh) (passed in so callers can reuse it).
//! \param processors in a -parallel run (a collective then), this rank's processor faces
//!        (exchange_processor_faces): they are checked as coupled faces, and the regions, the
//!        bounding box, the directions and the boundary openness are global; the rest of the
//!        report is this rank's, reduce_report() (parallel_report.h) combines the ranks.
//! \throw InvalidInput if labels are out of range (files are validated by the reader).
QualityReport check_mesh(const PolyMesh& mesh, const CompactList& cell_faces,
                         const MeshGeometry& geometry, const CheckMeshSettings& settings,
                         const ProcessorFaces* processors = nullptr);
//! \throw InvalidInput unless cell_faces has one entry per cell of mesh (check_mesh's own
//! test, for callers that compute the geometry from cell_faces first).
void require_cell_faces_of(const PolyMesh& mesh, const CompactList& cell_faces);
//! Convenience overload computing cell_faces and the geometry.
QualityReport check_mesh(const PolyMesh& mesh, const CheckMeshSettings& settings);

} // namespace meshmorph
