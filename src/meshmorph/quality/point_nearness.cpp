// SPDX-License-Identifier: GPL-3.0-or-later
// checkPointNearness's sorted sweep (serial; the sort is the cost).
#include "meshmorph/quality/point_nearness.h"

#include <algorithm>
#include <numeric>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

std::vector<char> near_points(const PolyMesh& mesh, double dist_sqr)
{
    const Index n = mesh.n_points();
    std::vector<double> mag_sqr(static_cast<std::size_t>(n));
    for (Index p = 0; p < n; ++p)
        mag_sqr[p] = detail::mag_sqr(detail::row(mesh.points, p));
    // SortableList: a stable sort of the indices by value.
    std::vector<Index> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), Index{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](Index a, Index b) { return mag_sqr[a] < mag_sqr[b]; });
    std::vector<char> marked(static_cast<std::size_t>(n), 0);
    for (Index i = 1; i < n; ++i)
    {
        const Index p = order[i];
        const double lower = mag_sqr[p] - dist_sqr;
        for (Index j = i - 1; j >= 0 && mag_sqr[order[j]] > lower; --j)
        {
            const Index q = order[j];
            if (detail::mag_sqr(detail::row(mesh.points, p) - detail::row(mesh.points, q)) <
                dist_sqr)
                marked[p] = marked[q] = 1;
        }
    }
    return marked;
}

} // namespace meshmorph
