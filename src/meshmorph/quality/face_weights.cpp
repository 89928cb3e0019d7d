// SPDX-License-Identifier: GPL-3.0-or-later
// Face weights and volume ratios in OpenFOAM's operation order.
#include "meshmorph/quality/face_weights.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/quality/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

Eigen::VectorXd face_weights(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_int = mesh.n_internal_faces();
    Eigen::VectorXd weight(n_int);
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
    for (Index f = 0; f < n_int; ++f)
    {
        const FoamVector fc = row(g.face_centres, f);
        const FoamVector fa = row(g.face_areas, f);
        const double d_own = std::abs(detail::dot(fa, fc - row(g.cell_centres, mesh.owner[f])));
        const double d_nei = std::abs(detail::dot(fa, row(g.cell_centres, mesh.neighbour[f]) - fc));
        weight[f] = std::min(d_nei, d_own) / (d_nei + d_own + constants::vsmall);
    }
    return weight;
}

Eigen::VectorXd face_volume_ratio(const PolyMesh& mesh, const Eigen::VectorXd& cell_volumes)
{
    const Index n_int = mesh.n_internal_faces();
    Eigen::VectorXd ratio(n_int);
    for (Index f = 0; f < n_int; ++f)
    {
        const double vo = cell_volumes[mesh.owner[f]];
        const double vn = cell_volumes[mesh.neighbour[f]];
        ratio[f] = std::min(vo, vn) / (std::max(vo, vn) + constants::vsmall);
    }
    return ratio;
}

} // namespace meshmorph
