// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Where a morph's invalid cells are: the patches they touch. A refusal that names
//! them points the user at the prescriptions to change (in practice a moving patch meeting
//! a fixed one, where the prescribed displacement jumps).
#pragma once

#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::morph
{

//! How many invalid cells have a point on a patch.
struct PatchCells
{
    std::string patch;
    Index cells = 0;
};

//! \brief Per patch (processor patches left out), the invalid cells (a volume below
//! VSMALL or a wrongly oriented face pyramid of their own, checkMesh's two criteria) that
//! have a point on it, summed over the ranks of `comm` (a collective: every rank holds the
//! same patches first, as decomposePar writes them).
//! Patches no invalid cell touches are left out; the most touched first.
std::vector<PatchCells> invalid_cells_by_patch(const PolyMesh& mesh, const CompactList& cell_faces,
                                               const MeshGeometry& geometry,
                                               const parallel::Communicator& comm);

//! "bottomWall (812 cells), sides_half0 (40 cells)": the first `at_most`, then "and N more
//! patches"; "" for none.
std::string describe(const std::vector<PatchCells>& counts, std::size_t at_most = 4);

} // namespace meshmorph::morph
