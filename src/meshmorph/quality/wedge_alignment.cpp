// SPDX-License-Identifier: GPL-3.0-or-later
// checkWedges (OpenFOAM v1912 checkMesh/checkGeometry.C) in its order and tolerances.
#include "meshmorph/quality/wedge_alignment.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <span>
#include <utility>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;

namespace
{

FoamVector foam(const Vector3& v)
{
    return {v.x(), v.y(), v.z()};
}

bool same_axis(const WedgeGeometry& a, const WedgeGeometry& b)
{
    return std::abs(detail::dot(foam(a.axis), foam(b.axis))) >= 1 - 1e-3;
}

//! The first point of the patch, in OpenFOAM's meshPoints order (first use in face
//! order), farther than ROOTSMALL from the plane through the first one; false if none.
bool off_plane_point(const PolyMesh& mesh, const Patch& patch, const FoamVector& normal,
                     WedgeFindings& found)
{
    const double rootsmall = std::sqrt(constants::small);
    const FoamVector p0 = detail::row(mesh.points, mesh.faces[patch.start_face][0]);
    std::vector<char> seen(static_cast<std::size_t>(mesh.n_points()), 0);
    for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
        for (const Index p : mesh.faces[f])
        {
            if (std::exchange(seen[static_cast<std::size_t>(p)], 1))
                continue;
            const FoamVector pt = detail::row(mesh.points, p);
            const double d = std::abs(detail::dot(pt - p0, normal));
            if (d > rootsmall)
            {
                found.off_plane_point = {pt.x, pt.y, pt.z};
                found.off_plane_distance = d;
                return true;
            }
        }
    return false;
}

//! The edges of the patch's faces (p0 < p1), appended.
void append_patch_edges(const PolyMesh& mesh, const Patch& patch, std::vector<Edge>& edges)
{
    for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
    {
        const std::span<const Index> face = mesh.faces[f];
        for (std::size_t i = 0; i < face.size(); ++i)
        {
            const Index a = face[i], b = face[(i + 1) % face.size()];
            edges.push_back({std::min(a, b), std::max(a, b)});
        }
    }
}

//! Finds the first problem of wedges[i] (opposite, axis, planarity), if any.
WedgeFindings::Problem wedge_problem(const PolyMesh& mesh, const std::vector<WedgeGeometry>& wedges,
                                     std::size_t i, WedgeFindings& found)
{
    const WedgeGeometry& w = wedges[i];
    const Index opposite = opposite_wedge(mesh, wedges, i);
    if (opposite < 0)
        return WedgeFindings::Problem::no_opposite;
    const WedgeGeometry& o = wedges[static_cast<std::size_t>(opposite)];
    if (!same_axis(w, o))
    {
        found.opposite_axis = o.axis;
        return WedgeFindings::Problem::different_axes;
    }
    const Patch& patch = mesh.patches[static_cast<std::size_t>(w.patch)];
    if (off_plane_point(mesh, patch, foam(w.normal), found))
        return WedgeFindings::Problem::not_planar;
    return WedgeFindings::Problem::none;
}

} // namespace

Index opposite_wedge(const PolyMesh& mesh, const std::vector<WedgeGeometry>& wedges, std::size_t i)
{
    const WedgeGeometry& w = wedges[i];
    const Index n_faces = mesh.patches[static_cast<std::size_t>(w.patch)].n_faces;
    for (std::size_t j = 0; j < wedges.size(); ++j)
    {
        if (j == i)
            continue;
        const WedgeGeometry& o = wedges[j];
        // The angle of o's normal to w's (not o's) centre normal.
        const double cos_angle = detail::dot(foam(w.centre_normal), foam(o.normal));
        if (mesh.patches[static_cast<std::size_t>(o.patch)].n_faces == n_faces && same_axis(o, w) &&
            std::abs(cos_angle - w.cos_angle) >= 1e-3)
            return static_cast<Index>(j);
    }
    return -1;
}

WedgeFindings wedge_findings(const PolyMesh& mesh, const std::vector<WedgeGeometry>& wedges,
                             const MeshDirections& directions)
{
    WedgeFindings found;
    std::vector<Edge> wedge_edges;
    for (std::size_t i = 0; i < wedges.size(); ++i)
    {
        found.n_examined = i + 1;
        found.problem = wedge_problem(mesh, wedges, i, found);
        if (found.problem != WedgeFindings::Problem::none)
            return found;
        append_patch_edges(mesh, mesh.patches[static_cast<std::size_t>(wedges[i].patch)],
                           wedge_edges);
    }
    // Edges on a wedge are exempt: they lie in the wedge plane, tilted off the valid ones.
    std::sort(wedge_edges.begin(), wedge_edges.end());
    const std::vector<Edge> all = non_aligned_edges(mesh, directions);
    std::set_difference(all.begin(), all.end(), wedge_edges.begin(), wedge_edges.end(),
                        std::back_inserter(found.non_aligned));
    return found;
}

} // namespace meshmorph
