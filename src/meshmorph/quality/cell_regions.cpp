// SPDX-License-Identifier: GPL-3.0-or-later
// Cell regions by union-find over the internal faces.
#include "meshmorph/quality/cell_regions.h"

#include <algorithm>

#include "meshmorph/quality/disjoint_sets.h"

namespace meshmorph
{

std::vector<std::vector<Index>> cell_regions(const PolyMesh& mesh)
{
    const Index n_cells = mesh.n_cells;
    detail::DisjointSets sets(n_cells);
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
    {
        const Index a = sets.find(mesh.owner[f]), b = sets.find(mesh.neighbour[f]);
        if (a != b)
            sets.link(std::max(a, b), std::min(a, b));
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

} // namespace meshmorph
