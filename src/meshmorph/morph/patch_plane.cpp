// SPDX-License-Identifier: GPL-3.0-or-later
// The plane of a planar patch: mean normal from the face areas, flatness from the points.
#include "meshmorph/morph/patch_plane.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph::morph
{

namespace
{

//! The normal of the patch's net area vector, or nullopt when it is small against the
//! total area (a closed or strongly curved patch has no plane).
std::optional<Vector3> mean_normal(const PolyMesh& mesh, const Patch& patch)
{
    Vector3 area = Vector3::Zero();
    double total_area = 0.0;
    for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
    {
        const Vector3 a = face_area_vector(mesh, f);
        area += a;
        total_area += a.norm();
    }
    if (area.norm() < 0.5 * total_area || area.norm() <= constants::vsmall)
        return std::nullopt;
    return area.normalized();
}

} // namespace

std::optional<std::pair<Vector3, double>> patch_plane(const PolyMesh& mesh, const Patch& patch,
                                                      double tolerance)
{
    if (patch.n_faces == 0)
        return std::nullopt;
    const std::optional<Vector3> n = mean_normal(mesh, patch);
    if (!n)
        return std::nullopt;
    const std::vector<Index> pts = patch_points(mesh, patch);
    Vector3 lo = Vector3::Constant(constants::vgreat);
    Vector3 hi = Vector3::Constant(-constants::vgreat);
    Vector3 centre = Vector3::Zero();
    for (Index p : pts)
    {
        const Vector3 x = mesh.points.row(p).transpose();
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
        centre += x;
    }
    centre /= static_cast<double>(pts.size());
    const double offset = n->dot(centre);
    double deviation = 0.0;
    for (Index p : pts)
        deviation = std::max(deviation, std::abs(n->dot(mesh.points.row(p).transpose()) - offset));
    if (deviation > tolerance * (hi - lo).norm())
        return std::nullopt;
    return std::make_pair(*n, offset);
}

} // namespace meshmorph::morph
