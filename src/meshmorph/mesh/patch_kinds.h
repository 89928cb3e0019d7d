// SPDX-License-Identifier: GPL-3.0-or-later
//! \file What kind of patch a polyMesh patch is, by its `type`, as OpenFOAM's polyPatch
//! classes decide it: the predicates every module asks (the checker, the morph's patch
//! assignment, the decomposed-case code), in one place.
#pragma once

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! \brief Whether checkMesh couples the patch's faces with another patch of this mesh:
//! cyclic and cyclicSlip (cyclicPolyPatch and its derived types).
bool is_coupled_patch(const Patch& patch);

//! \brief processor and processorCyclic patches: the faces a decomposed mesh shares with
//! another rank (internal faces of the undecomposed mesh).
bool is_processor_patch(const Patch& patch);

//! \brief processorCyclic: a processor patch that is also half of a cyclic split by the
//! decomposition.
bool is_processor_cyclic_patch(const Patch& patch);

} // namespace meshmorph
