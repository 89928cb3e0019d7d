// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A -parallel morph's view of the whole mesh: this rank's labels in the undecomposed
//! mesh (decomposePar's pointProcAddressing), counts over all ranks, and the distributed
//! check of the morphed mesh (checkMeshQuality -parallel's). Serial runs pass an empty
//! Decomposition and get the serial answers.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/decomposition.h"
#include "meshmorph/morph/patch_assignment.h"
#include "meshmorph/parallel/communicator.h"
#include "meshmorph/quality/check_settings.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::morph
{

//! This rank's point labels in the undecomposed mesh (decomposePar's pointProcAddressing).
Decomposition read_decomposition(const io::FoamPolyMesh& foam, const parallel::Communicator& comm);

//! A count over the whole mesh: cells are split between the ranks; points are shared, and
//! the undecomposed mesh has (largest label + 1) of them.
Index global_count(const Decomposition& d, Index local, bool points);

//! The patches' point counts over every rank (a shared point once), for the set-up lines.
void set_global_patch_points(const PolyMesh& mesh, const Decomposition& d,
                             std::vector<PatchAssignment>& patches);

//! check_mesh, or in a -parallel run the distributed check: every rank checks its part with
//! the processor faces coupled and the master holds the report of the whole mesh; the two
//! counts a morph is judged by are summed on every rank, so that all refuse alike.
QualityReport check_morph_mesh(const PolyMesh& mesh, const CompactList& cf,
                               const MeshGeometry& geometry, const CheckMeshSettings& settings,
                               const Decomposition& d);

} // namespace meshmorph::morph
