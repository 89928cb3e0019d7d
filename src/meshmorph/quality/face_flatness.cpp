// SPDX-License-Identifier: GPL-3.0-or-later
// Face flatness in OpenFOAM's operation order.
#include "meshmorph/quality/face_flatness.h"

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::row;

namespace
{

double fan_area(const PolyMesh& mesh, const MeshGeometry& g, Index f)
{
    const std::span<const Index> face = mesh.faces[f];
    const detail::FoamVector fc = row(g.face_centres, f);
    double sum = 0;
    for (std::size_t i = 0; i < face.size(); ++i)
        sum += detail::mag(detail::tri_area_normal(
            row(mesh.points, face[i]), row(mesh.points, face[(i + 1) % face.size()]), fc));
    return sum;
}

} // namespace

Eigen::VectorXd face_fan_areas(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_faces = mesh.n_faces();
    Eigen::VectorXd fan(n_faces);
#pragma omp parallel for schedule(dynamic,                                                         \
                                  detail::loop_piece) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
        fan[f] = fan_area(mesh, g, f);
    return fan;
}

Eigen::VectorXd face_flatness(const PolyMesh& mesh, const MeshGeometry& g,
                              const Eigen::VectorXd& mag_area)
{
    const Index n_faces = mesh.n_faces();
    Eigen::VectorXd flatness(n_faces);
#pragma omp parallel for schedule(dynamic,                                                         \
                                  detail::loop_piece) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
        flatness[f] = mesh.faces.item_size(f) <= 3 || mag_area[f] <= constants::rootvsmall
                          ? 1.0
                          : mag_area[f] / (fan_area(mesh, g, f) + constants::rootvsmall);
    return flatness;
}

} // namespace meshmorph
