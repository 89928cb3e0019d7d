// SPDX-License-Identifier: GPL-3.0-or-later
// Face pyramid volumes and orientation errors in OpenFOAM's operation order.
#include "meshmorph/quality/face_pyramids.h"

#include <utility>

#include "meshmorph/mesh/foam_vector.h"
#include "meshmorph/quality/cell_validity.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

//! The owner and (internal faces) neighbour pyramid volumes of face f.
std::pair<double, double> pyramid_volumes(const PolyMesh& mesh, const MeshGeometry& g, Index f)
{
    const FoamVector cf = row(g.face_centres, f);
    const FoamVector af = row(g.face_areas, f);
    const double own = -((1.0 / 3.0) * detail::dot(af, row(g.cell_centres, mesh.owner[f]) - cf));
    if (f >= mesh.n_internal_faces())
        return {own, 0.0};
    return {own, (1.0 / 3.0) * detail::dot(af, row(g.cell_centres, mesh.neighbour[f]) - cf)};
}

} // namespace

FacePyramidVolumes face_pyramid_volumes(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_faces = mesh.n_faces();
    const Index n_int = mesh.n_internal_faces();
    FacePyramidVolumes v{Eigen::VectorXd(n_faces), Eigen::VectorXd(n_int)};
#pragma omp parallel for schedule(dynamic,                                                         \
                                  detail::loop_piece) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
    {
        const auto [own, nei] = pyramid_volumes(mesh, g, f);
        v.owner[f] = own;
        if (f < n_int)
            v.neighbour[f] = nei;
    }
    return v;
}

std::vector<char> face_pyramid_errors(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_faces = mesh.n_faces();
    std::vector<char> n_err(static_cast<std::size_t>(n_faces), 0);
#pragma omp parallel for schedule(dynamic,                                                         \
                                  detail::loop_piece) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
    {
        const auto [own, nei] = pyramid_volumes(mesh, g, f);
        n_err[f] = static_cast<char>(wrongly_oriented(own) +
                                     (f < mesh.n_internal_faces() && wrongly_oriented(nei)));
    }
    return n_err;
}

} // namespace meshmorph
