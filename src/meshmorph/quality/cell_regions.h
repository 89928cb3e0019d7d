// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Cell regions: the sets of cells connected through internal faces (OpenFOAM
//! regionSplit, as checkMesh numbers them).
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! \brief The regions, each its cells in ascending order; region 0 holds cell 0, region 1
//! the lowest cell not in region 0, ...
std::vector<std::vector<Index>> cell_regions(const PolyMesh& mesh);

} // namespace meshmorph
