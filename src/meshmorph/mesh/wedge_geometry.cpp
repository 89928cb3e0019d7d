// SPDX-License-Identifier: GPL-3.0-or-later
// Wedge patch geometry in OpenFOAM's operation order (wedgePolyPatch::calcGeometry,
// face::areaNormal, Vector::normalise).
#include "meshmorph/mesh/wedge_geometry.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;

namespace
{

//! face::areaNormal: a triangle directly, else the fan of triangles around the vertex mean
//! (not around the face centre, as the mesh's face areas are).
FoamVector area_normal(const PolyMesh& mesh, Index f)
{
    const std::span<const Index> face = mesh.faces[f];
    const std::size_t n = face.size();
    const auto p = [&](std::size_t i) { return detail::row(mesh.points, face[i]); };
    if (n == 3)
        return detail::tri_area_normal(p(0), p(1), p(2));
    FoamVector centre;
    for (std::size_t i = 0; i < n; ++i)
        centre += p(i);
    centre /= static_cast<double>(n);
    FoamVector sum;
    for (std::size_t i = 0; i < n; ++i)
        sum += detail::tri_area_normal(p(i), p((i + 1) % n), centre);
    return sum;
}

//! Vector::normalise and face::unitNormal: zero below ROOTVSMALL.
FoamVector normalised(const FoamVector& v)
{
    const double m = detail::mag(v);
    return m < constants::rootvsmall ? FoamVector{} : v / m;
}

//! The component of the centre normal: how far |c| exceeds 0.5, with c's sign (sign(0) = 1).
double centre_component(double c)
{
    return (c >= 0 ? 1.0 : -1.0) * (std::max(std::abs(c), 0.5) - 0.5);
}

Vector3 to_vector3(const FoamVector& v)
{
    return {v.x, v.y, v.z};
}

} // namespace

WedgeGeometry wedge_geometry(const PolyMesh& mesh, Index patch)
{
    const Patch& pp = mesh.patches[static_cast<std::size_t>(patch)];
    FoamVector sum;
    for (Index f = pp.start_face; f < pp.start_face + pp.n_faces; ++f)
        sum += normalised(area_normal(mesh, f));
    const FoamVector n = sum / static_cast<double>(pp.n_faces); // gAverage
    const FoamVector centre =
        normalised({centre_component(n.x), centre_component(n.y), centre_component(n.z)});
    const FoamVector cross = detail::cross(centre, n);
    const double mag_axis = detail::mag(cross);
    // A wedge lying in a coordinate plane has no axis: OpenFOAM refuses such a mesh; zero here.
    const FoamVector axis = mag_axis < constants::small ? FoamVector{} : cross / mag_axis;
    WedgeGeometry w;
    w.patch = patch;
    w.normal = to_vector3(n);
    w.centre_normal = to_vector3(centre);
    w.cos_angle = detail::dot(centre, n);
    w.axis = to_vector3(axis);
    return w;
}

std::vector<WedgeGeometry> wedge_geometries(const PolyMesh& mesh)
{
    std::vector<WedgeGeometry> wedges;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        if (mesh.patches[i].type == "wedge" && mesh.patches[i].n_faces > 0)
            wedges.push_back(wedge_geometry(mesh, static_cast<Index>(i)));
    return wedges;
}

} // namespace meshmorph
