// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Concave cells by face planes (OpenFOAM primitiveMesh::checkConcaveCells): a cell is
//! concave when the centre of one of its faces is not strictly behind the plane of another.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief Per cell, whether some face centre lies at or in front of (by more than -1e-6 of
//! the unit distance) the outward plane of another of its faces. OpenMP over cells.
//! \return nCells flags.
std::vector<char> concave_cells(const PolyMesh& mesh, const CompactList& cell_faces,
                                const MeshGeometry& geometry);

} // namespace meshmorph
