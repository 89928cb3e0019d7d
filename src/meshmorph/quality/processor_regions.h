// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The cell regions of a decomposed mesh (checkMesh -parallel's regionSplit): regions
//! of the ranks that meet across processor faces are one region.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/processor_faces.h"

namespace meshmorph
{

//! \brief Per global region (numbered by the lowest rank, then the lowest cell there), this
//! rank's cells in it (ascending; empty where the region has none here). A collective.
//! \param local cell_regions(mesh) of this rank.
std::vector<std::vector<Index>> global_cell_regions(const PolyMesh& mesh,
                                                    const std::vector<std::vector<Index>>& local,
                                                    const ProcessorFaces& processors);

} // namespace meshmorph
