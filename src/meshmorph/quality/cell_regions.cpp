// SPDX-License-Identifier: GPL-3.0-or-later
// Cell regions by union-find over the internal and cyclic faces.
#include "meshmorph/quality/cell_regions.h"

#include <algorithm>

#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/patch_kinds.h"
#include "meshmorph/quality/disjoint_sets.h"

namespace meshmorph
{

std::vector<std::vector<Index>> cell_regions(const PolyMesh& mesh)
{
    const Index n_cells = mesh.n_cells;
    detail::DisjointSets sets(n_cells);
    const auto join = [&](Index a, Index b)
    {
        a = sets.find(a);
        b = sets.find(b);
        if (a != b)
            sets.link(std::max(a, b), std::min(a, b));
    };
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
        join(mesh.owner[f], mesh.neighbour[f]);
    // regionSplit::fillSeedMask: face i of a cyclic and face i of its neighbourPatch
    // (cyclicPolyPatch::transformGlobalFace) share their region.
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
    {
        const Patch& p = mesh.patches[i];
        if (!is_coupled_patch(p) || p.n_faces == 0)
            continue;
        const Patch& nbr =
            mesh.patches[static_cast<std::size_t>(cyclic_neighbour_patch(mesh, Index(i)))];
        for (Index k = 0; k < std::min(p.n_faces, nbr.n_faces); ++k)
            join(mesh.owner[p.start_face + k], mesh.owner[nbr.start_face + k]);
    }
    std::vector<Index> region_of_root(static_cast<std::size_t>(n_cells), -1);
    std::vector<std::vector<Index>> regions;
    for (Index cell = 0; cell < n_cells; ++cell)
    {
        const Index r = sets.find(cell);
        if (region_of_root[r] < 0)
        {
            region_of_root[r] = static_cast<Index>(regions.size());
            regions.emplace_back();
        }
        regions[region_of_root[r]].push_back(cell);
    }
    return regions;
}

std::vector<Index> region_of_cells(const std::vector<std::vector<Index>>& regions, Index n_cells)
{
    std::vector<Index> region(static_cast<std::size_t>(n_cells), -1);
    for (std::size_t r = 0; r < regions.size(); ++r)
        for (Index cell : regions[r])
            region[static_cast<std::size_t>(cell)] = static_cast<Index>(r);
    return region;
}

} // namespace meshmorph
