// SPDX-License-Identifier: GPL-3.0-or-later
// Point -> faces addressing by counting sort.
#include "meshmorph/mesh/point_faces.h"

#include <numeric>

namespace meshmorph
{

CompactList point_faces(const PolyMesh& mesh)
{
    CompactList pf;
    pf.offsets.assign(static_cast<std::size_t>(mesh.n_points()) + 1, 0);
    for (Index p : mesh.faces.values)
        ++pf.offsets[p + 1];
    std::partial_sum(pf.offsets.begin(), pf.offsets.end(), pf.offsets.begin());
    pf.values.resize(mesh.faces.values.size());
    std::vector<Index> fill(pf.offsets.begin(), pf.offsets.end() - 1);
    for (Index f = 0; f < mesh.n_faces(); ++f)
        for (Index p : mesh.faces[f])
            pf.values[fill[p]++] = f;
    return pf;
}

} // namespace meshmorph
