// SPDX-License-Identifier: GPL-3.0-or-later
// Face weights and volume ratios in OpenFOAM's operation order.
#include "meshmorph/quality/face_weights.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

double weight(const FoamVector& fc, const FoamVector& fa, const FoamVector& own_cc,
              const FoamVector& nei_cc)
{
    const double d_own = std::abs(detail::dot(fa, fc - own_cc));
    const double d_nei = std::abs(detail::dot(fa, nei_cc - fc));
    return std::min(d_nei, d_own) / (d_nei + d_own + constants::vsmall);
}

double ratio(double vo, double vn)
{
    return std::min(vo, vn) / (std::max(vo, vn) + constants::vsmall);
}

} // namespace

Eigen::VectorXd face_weights(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_int = mesh.n_internal_faces();
    Eigen::VectorXd weights(n_int);
#pragma omp parallel for schedule(dynamic, detail::loop_piece) if (mesh.n_faces() >                \
                                                                   detail::parallel_threshold)
    for (Index f = 0; f < n_int; ++f)
        weights[f] =
            weight(row(g.face_centres, f), row(g.face_areas, f), row(g.cell_centres, mesh.owner[f]),
                   row(g.cell_centres, mesh.neighbour[f]));
    return weights;
}

Eigen::VectorXd face_weights(const PolyMesh& mesh, const MeshGeometry& g,
                             const CoupledFaces& coupled)
{
    const Index n_int = mesh.n_internal_faces();
    Eigen::VectorXd weights = Eigen::VectorXd::Ones(mesh.n_faces());
    weights.head(n_int) = face_weights(mesh, g);
    for (Index f = n_int; f < mesh.n_faces(); ++f)
        if (coupled.coupled_boundary(mesh, f))
            weights[f] = weight(row(g.face_centres, f), row(g.face_areas, f),
                                row(g.cell_centres, mesh.owner[f]),
                                row(coupled.neighbour_cell_centres, f - n_int));
    return weights;
}

Eigen::VectorXd face_volume_ratio(const PolyMesh& mesh, const Eigen::VectorXd& cell_volumes)
{
    const Index n_int = mesh.n_internal_faces();
    Eigen::VectorXd ratios(n_int);
    for (Index f = 0; f < n_int; ++f)
        ratios[f] = ratio(cell_volumes[mesh.owner[f]], cell_volumes[mesh.neighbour[f]]);
    return ratios;
}

Eigen::VectorXd face_volume_ratio(const PolyMesh& mesh, const Eigen::VectorXd& cell_volumes,
                                  const CoupledFaces& coupled)
{
    const Index n_int = mesh.n_internal_faces();
    Eigen::VectorXd ratios = Eigen::VectorXd::Ones(mesh.n_faces());
    ratios.head(n_int) = face_volume_ratio(mesh, cell_volumes);
    for (Index f = n_int; f < mesh.n_faces(); ++f)
        if (coupled.coupled_boundary(mesh, f))
            ratios[f] =
                ratio(cell_volumes[mesh.owner[f]], coupled.neighbour_cell_volumes[f - n_int]);
    return ratios;
}

} // namespace meshmorph
