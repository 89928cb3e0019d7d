// SPDX-License-Identifier: GPL-3.0-or-later
// Face skewness in OpenFOAM's operation order.
#include "meshmorph/quality/face_skewness.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/quality/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

double skewness_of(const PolyMesh& mesh, const MeshGeometry& g, Index f)
{
    constexpr double rootvsmall = constants::rootvsmall;
    const FoamVector cf = row(g.face_centres, f);
    const FoamVector af = row(g.face_areas, f);
    const FoamVector own_cc = row(g.cell_centres, mesh.owner[f]);
    const FoamVector cpf = cf - own_cc;
    FoamVector d;
    double factor;
    if (f < mesh.n_internal_faces())
    {
        d = row(g.cell_centres, mesh.neighbour[f]) - own_cc;
        factor = 0.2;
    }
    else
    {
        FoamVector normal = af;
        normal /= detail::mag(normal) + rootvsmall;
        d = detail::dot(normal, cpf) * normal;
        factor = 0.4;
    }
    const FoamVector sv = cpf - (detail::dot(af, cpf) / (detail::dot(af, d) + rootvsmall)) * d;
    const FoamVector sv_hat = sv / (detail::mag(sv) + rootvsmall);
    double fd = factor * detail::mag(d) + rootvsmall;
    for (Index p : mesh.faces[f])
        fd = std::max(fd, std::abs(detail::dot(sv_hat, row(mesh.points, p) - cf)));
    return detail::mag(sv) / fd;
}

} // namespace

Eigen::VectorXd face_skewness(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_faces = mesh.n_faces();
    Eigen::VectorXd skewness(n_faces);
#pragma omp parallel for schedule(static) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
        skewness[f] = skewness_of(mesh, g, f);
    return skewness;
}

Eigen::VectorXd cell_skewness(const CompactList& cell_faces, const Eigen::VectorXd& skewness)
{
    const Index n_cells = cell_faces.size();
    Eigen::VectorXd cell(n_cells);
#pragma omp parallel for schedule(static) if (skewness.size() > detail::parallel_threshold)
    for (Index c = 0; c < n_cells; ++c)
    {
        double max_skew = 0;
        for (Index f : cell_faces[c])
            max_skew = std::max(max_skew, skewness[f]);
        cell[c] = max_skew;
    }
    return cell;
}

} // namespace meshmorph
