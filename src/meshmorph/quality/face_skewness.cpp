// SPDX-License-Identifier: GPL-3.0-or-later
// Face skewness in OpenFOAM's operation order.
#include "meshmorph/quality/face_skewness.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

//! Skewness of face f; `across` is the cell centre on the other side, if any.
double skewness_of(const PolyMesh& mesh, const MeshGeometry& g, Index f, const FoamVector* across)
{
    constexpr double rootvsmall = constants::rootvsmall;
    const FoamVector cf = row(g.face_centres, f);
    const FoamVector af = row(g.face_areas, f);
    const FoamVector own_cc = row(g.cell_centres, mesh.owner[f]);
    const FoamVector cpf = cf - own_cc;
    FoamVector d;
    double factor;
    if (across)
    {
        d = *across - own_cc;
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
    {
        const FoamVector across =
            f < mesh.n_internal_faces() ? row(g.cell_centres, mesh.neighbour[f]) : FoamVector{};
        skewness[f] = skewness_of(mesh, g, f, f < mesh.n_internal_faces() ? &across : nullptr);
    }
    return skewness;
}

Eigen::VectorXd face_skewness(const PolyMesh& mesh, const MeshGeometry& g,
                              const CoupledFaces& coupled)
{
    Eigen::VectorXd skewness = face_skewness(mesh, g);
    const Index n_int = mesh.n_internal_faces();
    for (Index f = n_int; f < mesh.n_faces(); ++f)
        if (coupled.coupled_boundary(mesh, f))
        {
            const FoamVector across = row(coupled.neighbour_cell_centres, f - n_int);
            skewness[f] = skewness_of(mesh, g, f, &across);
        }
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
