// SPDX-License-Identifier: GPL-3.0-or-later
// Edge lengths in OpenFOAM's order (serial: the short-edge marking depends on it).
#include "meshmorph/quality/edge_lengths.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

EdgeLengths edge_lengths(const PolyMesh& mesh, double min_length_sqr)
{
    constexpr double great = constants::great;
    double min_len = great * great, max_len = -great * great;
    EdgeLengths r;
    r.short_edge_points.assign(static_cast<std::size_t>(mesh.n_points()), 0);
    std::vector<char>& marked = r.short_edge_points;
    for (Index f = 0; f < mesh.n_faces(); ++f)
    {
        const std::span<const Index> face = mesh.faces[f];
        for (std::size_t i = 0; i < face.size(); ++i)
        {
            const Index a = face[i], b = face[(i + 1) % face.size()];
            const double len =
                detail::mag_sqr(detail::row(mesh.points, a) - detail::row(mesh.points, b));
            if (len < min_length_sqr)
            {
                // OpenFOAM: if (set.insert(a) || set.insert(b)) nSmall++ (short-circuit).
                if (!marked[a])
                {
                    marked[a] = 1;
                    ++r.n_short;
                }
                else if (!marked[b])
                {
                    marked[b] = 1;
                    ++r.n_short;
                }
            }
            min_len = std::min(min_len, len);
            max_len = std::max(max_len, len);
        }
    }
    r.min_length = std::sqrt(min_len);
    r.max_length = std::sqrt(max_len);
    return r;
}

} // namespace meshmorph
