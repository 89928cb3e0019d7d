// SPDX-License-Identifier: GPL-3.0-or-later
// Face orthogonality in OpenFOAM's operation order.
#include "meshmorph/quality/face_orthogonality.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

double orthogonality(const FoamVector& own_cc, const FoamVector& nei_cc, const FoamVector& s,
                     double eps)
{
    const FoamVector d = nei_cc - own_cc;
    return detail::dot(d, s) / (detail::mag(d) * detail::mag(s) + eps);
}

} // namespace

double internal_face_orthogonality(const PolyMesh& mesh, const MeshGeometry& g, Index f, double eps)
{
    return orthogonality(row(g.cell_centres, mesh.owner[f]), row(g.cell_centres, mesh.neighbour[f]),
                         row(g.face_areas, f), eps);
}

Eigen::VectorXd face_orthogonality(const PolyMesh& mesh, const MeshGeometry& g, double eps)
{
    const Index n_int = mesh.n_internal_faces();
    Eigen::VectorXd ortho = Eigen::VectorXd::Ones(mesh.n_faces());
#pragma omp parallel for schedule(dynamic, detail::loop_piece) if (mesh.n_faces() >                \
                                                                   detail::parallel_threshold)
    for (Index f = 0; f < n_int; ++f)
        ortho[f] = internal_face_orthogonality(mesh, g, f, eps);
    return ortho;
}

Eigen::VectorXd face_orthogonality(const PolyMesh& mesh, const MeshGeometry& g,
                                   const CoupledFaces& coupled, double eps)
{
    Eigen::VectorXd ortho = face_orthogonality(mesh, g, eps);
    const Index n_int = mesh.n_internal_faces();
    for (Index f = n_int; f < mesh.n_faces(); ++f)
        if (coupled.coupled_boundary(mesh, f))
            ortho[f] = coupled_face_orthogonality(mesh, g, coupled, f, eps);
    return ortho;
}

double coupled_face_orthogonality(const PolyMesh& mesh, const MeshGeometry& g,
                                  const CoupledFaces& coupled, Index f, double eps)
{
    return orthogonality(row(g.cell_centres, mesh.owner[f]),
                         row(coupled.neighbour_cell_centres, f - mesh.n_internal_faces()),
                         row(g.face_areas, f), eps);
}

double non_orthogonality_degrees(double cosine)
{
    return detail::rad_to_deg(std::acos(std::min(1.0, std::max(-1.0, cosine))));
}

Eigen::VectorXd cell_non_orthogonality(const CompactList& cell_faces,
                                       const Eigen::VectorXd& orthogonality)
{
    const Index n_cells = cell_faces.size();
    Eigen::VectorXd angle(n_cells);
#pragma omp parallel for schedule(dynamic, detail::loop_piece) if (orthogonality.size() >          \
                                                                   detail::parallel_threshold)
    for (Index cell = 0; cell < n_cells; ++cell)
    {
        double min_cos = 1;
        for (Index f : cell_faces[cell])
            min_cos = std::min(min_cos, orthogonality[f]);
        angle[cell] = non_orthogonality_degrees(min_cos);
    }
    return angle;
}

} // namespace meshmorph
