// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Cell regions: the sets of cells connected through internal and cyclic faces (OpenFOAM
//! regionSplit, as checkMesh numbers them).
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! \brief The regions, each its cells in ascending order; region 0 holds cell 0, region 1
//! the lowest cell not in region 0, ... Cells are connected through internal faces and
//! through the faces of cyclic (and cyclicSlip) patches, face i with face i of the
//! neighbourPatch, as serial regionSplit walks them; cyclicAMI, processor and other patches
//! connect nothing.
//! \throws InvalidInput if a cyclic patch names no cyclic neighbourPatch.
std::vector<std::vector<Index>> cell_regions(const PolyMesh& mesh);

//! \brief Per cell, the index of its region in `regions` (cell_regions(mesh)).
std::vector<Index> region_of_cells(const std::vector<std::vector<Index>>& regions, Index n_cells);

} // namespace meshmorph
