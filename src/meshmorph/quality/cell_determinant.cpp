// SPDX-License-Identifier: GPL-3.0-or-later
// Cell determinants in OpenFOAM's operation order.
#include "meshmorph/quality/cell_determinant.h"

#include <cmath>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

//! checkMesh's determinant of one cell (primitiveMeshTools::cellDeterminant).
//! `counts(f)`: face f joins two cells (internal or coupled).
template <class Counts>
double cell_determinant_of(std::span<const Index> faces, const MeshGeometry& g,
                           const MeshDirections& dirs, const Eigen::VectorXd& mag_area,
                           const Counts& counts)
{
    double avg = 0;
    Index n_internal = 0;
    for (Index f : faces)
        if (counts(f))
        {
            avg += mag_area[f];
            ++n_internal;
        }
    if (n_internal == 0 || avg < constants::rootvsmall)
        return 0;
    avg /= static_cast<double>(n_internal);
    double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
    for (Index f : faces)
        if (counts(f))
        {
            const FoamVector a = row(g.face_areas, f) / avg;
            xx += a.x * a.x;
            xy += a.x * a.y;
            xz += a.x * a.z;
            yy += a.y * a.y;
            yz += a.y * a.z;
            zz += a.z * a.z;
        }
    if (dirs.n_geometric() == 2)
    {
        if (dirs.geometric[0] == -1)
            xx = 1;
        if (dirs.geometric[1] == -1)
            yy = 1;
        if (dirs.geometric[2] == -1)
            zz = 1;
    }
    const double det =
        xx * yy * zz + xy * yz * xz + xz * xy * yz - xx * yz * yz - xy * xy * zz - xz * yy * xz;
    return std::abs(det) / 8.0;
}

template <class Counts>
Eigen::VectorXd cell_determinants(const PolyMesh& mesh, const CompactList& cell_faces,
                                  const MeshGeometry& g, const MeshDirections& dirs,
                                  const Eigen::VectorXd& mag_area, const Counts& counts)
{
    const Index n_cells = mesh.n_cells;
    Eigen::VectorXd det(n_cells);
    const bool one_d = dirs.n_geometric() == 1;
#pragma omp parallel for schedule(dynamic, detail::loop_piece) if (mesh.n_faces() >                \
                                                                   detail::parallel_threshold)
    for (Index cell = 0; cell < n_cells; ++cell)
        det[cell] = one_d ? 1.0 : cell_determinant_of(cell_faces[cell], g, dirs, mag_area, counts);
    return det;
}

} // namespace

Eigen::VectorXd cell_determinant(const PolyMesh& mesh, const CompactList& cell_faces,
                                 const MeshGeometry& g, const MeshDirections& dirs,
                                 const Eigen::VectorXd& mag_area)
{
    return cell_determinants(mesh, cell_faces, g, dirs, mag_area,
                             [&](Index f) { return mesh.is_internal_face(f); });
}

Eigen::VectorXd cell_determinant(const PolyMesh& mesh, const CompactList& cell_faces,
                                 const MeshGeometry& g, const MeshDirections& dirs,
                                 const Eigen::VectorXd& mag_area, const CoupledFaces& coupled)
{
    return cell_determinants(
        mesh, cell_faces, g, dirs, mag_area,
        [&](Index f) { return coupled.internal_or_coupled[static_cast<std::size_t>(f)] != 0; });
}

Eigen::VectorXd cell_area_determinant(const CompactList& cell_faces, const MeshGeometry& g)
{
    constexpr double vsmall = constants::vsmall;
    const Index n_cells = cell_faces.size();
    Eigen::VectorXd scaled(n_cells);
#pragma omp parallel for schedule(dynamic, detail::loop_piece) if (g.face_areas.rows() >           \
                                                                   detail::parallel_threshold)
    for (Index cell = 0; cell < n_cells; ++cell)
    {
        double t[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        double mag_sum = 0;
        for (Index f : cell_faces[cell])
        {
            const FoamVector a = row(g.face_areas, f);
            const double m = detail::mag(a);
            mag_sum += m;
            const FoamVector u = a / (m + vsmall);
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    t[i][j] += a[i] * u[j];
        }
        for (auto& r : t)
            for (double& v : r)
                v /= mag_sum + vsmall;
        const double det = t[0][0] * t[1][1] * t[2][2] + t[0][1] * t[1][2] * t[2][0] +
                           t[0][2] * t[1][0] * t[2][1] - t[0][0] * t[1][2] * t[2][1] -
                           t[0][1] * t[1][0] * t[2][2] - t[0][2] * t[1][1] * t[2][0];
        scaled[cell] = det / 0.037037037037037;
    }
    return scaled;
}

} // namespace meshmorph
