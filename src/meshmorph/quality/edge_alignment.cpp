// SPDX-License-Identifier: GPL-3.0-or-later
// Edge alignment in OpenFOAM's operation order.
#include "meshmorph/quality/edge_alignment.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

namespace
{

bool is_aligned(detail::FoamVector d, const Eigen::Vector3i& valid)
{
    d /= detail::mag(d);
    int n_empty = 0, n_valid = 0;
    for (int k = 0; k < 3; ++k)
        if (std::abs(d[k]) > 1e-6)
            (valid[k] == 0 ? n_empty : n_valid)++;
    return !(n_empty > 1 || (n_empty == 1 && n_valid > 0));
}

} // namespace

std::vector<Edge> non_aligned_edges(const PolyMesh& mesh, const MeshDirections& directions)
{
    const Eigen::Vector3i valid = (directions.geometric + Eigen::Vector3i::Ones()) / 2;
    std::vector<Edge> bad;
    for (Index f = 0; f < mesh.n_faces(); ++f)
    {
        const std::span<const Index> face = mesh.faces[f];
        for (std::size_t i = 0; i < face.size(); ++i)
        {
            const Index p0 = face[i], p1 = face[(i + 1) % face.size()];
            if (p0 >= p1)
                continue;
            const detail::FoamVector d =
                detail::row(mesh.points, p1) - detail::row(mesh.points, p0);
            if (detail::mag(d) <= constants::rootvsmall)
                continue;
            if (!is_aligned(d, valid))
                bad.push_back({p0, p1});
        }
    }
    std::sort(bad.begin(), bad.end());
    bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
    return bad;
}

} // namespace meshmorph
