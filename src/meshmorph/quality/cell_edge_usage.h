// SPDX-License-Identifier: GPL-3.0-or-later
//! \file How often each cell uses each of its edges (OpenFOAM primitiveMesh::checkCellsZipUp):
//! in a closed cell every edge is shared by exactly two of its faces.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

struct CellEdgeUsage
{
    std::vector<char> open;      //!< nCells: some edge used by one face only
    std::vector<char> over_used; //!< nCells: some edge used by more than two faces
};

//! \brief Edge use counts per cell. OpenMP over cells.
CellEdgeUsage cell_edge_usage(const PolyMesh& mesh, const CompactList& cell_faces);

} // namespace meshmorph
