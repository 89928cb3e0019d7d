// SPDX-License-Identifier: GPL-3.0-or-later
// Wedge partners found by rotation, and the axisymmetric projection of a displacement.
#include "meshmorph/morph/wedge_symmetry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <tuple>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "meshmorph/deform/uniform_grid.h"
#include "meshmorph/mesh/wedge_geometry.h"

namespace meshmorph::morph
{

namespace
{

//! A wedge plane: the points of its patch, their mean, and the unit normal (as OpenFOAM's
//! wedgePolyPatch finds it: the mean of the faces' unit normals, wedge_geometry.h).
struct WedgePlane
{
    Index patch = -1;
    std::vector<Index> points;
    Vector3 centroid = Vector3::Zero();
    Vector3 normal = Vector3::Zero();
};

WedgePlane wedge_plane(const PolyMesh& mesh, Index k)
{
    const Patch& patch = mesh.patches[std::size_t(k)];
    WedgePlane w;
    w.patch = k;
    w.points = patch_points(mesh, patch);
    for (Index p : w.points)
        w.centroid += mesh.points.row(p).transpose();
    w.centroid /= double(std::max<std::size_t>(w.points.size(), 1));
    w.normal = wedge_geometry(mesh, k).normal.normalized();
    return w;
}

//! The common line of the two planes: a point of it near the planes' points, and its unit
//! direction (either orientation: the rotation is built from it consistently).
std::pair<Vector3, Vector3> common_axis(const WedgePlane& a, const WedgePlane& b)
{
    const Vector3 axis = a.normal.cross(b.normal).normalized();
    Eigen::Matrix3d m;
    m.row(0) = a.normal.transpose();
    m.row(1) = b.normal.transpose();
    m.row(2) = axis.transpose();
    const Vector3 rhs(a.normal.dot(a.centroid), b.normal.dot(b.centroid),
                      axis.dot(0.5 * (a.centroid + b.centroid)));
    return {m.fullPivLu().solve(rhs), axis};
}

//! Unit direction from the axis to a plane's points, within the plane.
Vector3 radial(const WedgePlane& w, const Vector3& origin, const Vector3& axis)
{
    const Vector3 r = w.centroid - origin;
    return (r - r.dot(axis) * axis).normalized();
}

//! Per point, its shortest non-degenerate edge on the faces of `patch` (infinity elsewhere).
std::vector<double> shortest_edges(const PolyMesh& mesh, const Patch& patch)
{
    std::vector<double> shortest(std::size_t(mesh.n_points()),
                                 std::numeric_limits<double>::infinity());
    for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
    {
        const std::span<const Index> face = mesh.faces[f];
        for (std::size_t i = 0; i < face.size(); ++i)
        {
            const Index a = face[i], b = face[(i + 1) % face.size()];
            const double length = (mesh.points.row(a) - mesh.points.row(b)).norm();
            if (!(length > 0.0))
                continue; // a collapsed edge (on the axis)
            shortest[std::size_t(a)] = std::min(shortest[std::size_t(a)], length);
            shortest[std::size_t(b)] = std::min(shortest[std::size_t(b)], length);
        }
    }
    return shortest;
}

} // namespace

void WedgeSymmetry::apply(Points& d) const
{
    // Within its own plane first: the pair's mean (linear) then lies in both.
    for (const auto& [p, n] : plane_points)
        d.row(p) -= d.row(p).dot(n.transpose()) * n.transpose();
    coupled_mean(pairs, d);
    for (Index p : axis_points)
        d.row(p) = d.row(p).dot(axis.transpose()) * axis.transpose();
}

std::optional<WedgeSymmetry> find_wedge_symmetry(const PolyMesh& mesh)
{
    std::vector<Index> wedges;
    for (std::size_t k = 0; k < mesh.patches.size(); ++k)
        if (mesh.patches[k].type == "wedge" && mesh.patches[k].n_faces > 0)
            wedges.push_back(Index(k));
    if (wedges.size() != 2)
        return std::nullopt;
    const WedgePlane ref = wedge_plane(mesh, wedges[0]), other = wedge_plane(mesh, wedges[1]);
    if (!(ref.normal.cross(other.normal).norm() > 1e-9)) // parallel: not a wedge pair
        return std::nullopt;
    WedgeSymmetry s;
    std::tie(s.origin, s.axis) = common_axis(ref, other);
    const Vector3 r_ref = radial(ref, s.origin, s.axis), r_other = radial(other, s.origin, s.axis);
    const double angle = std::atan2(s.axis.dot(r_other.cross(r_ref)), r_other.dot(r_ref));
    s.to_reference = Eigen::AngleAxisd(angle, s.axis).toRotationMatrix();

    std::vector<char> on_ref(std::size_t(mesh.n_points()), 0);
    for (Index p : ref.points)
        on_ref[std::size_t(p)] = 1;
    Points ref_positions(Eigen::Index(ref.points.size()), 3);
    for (std::size_t i = 0; i < ref.points.size(); ++i)
        ref_positions.row(Eigen::Index(i)) = mesh.points.row(ref.points[i]);
    // A partner lies within 1e-3 of the point's shortest edge of where the rotation takes it
    // (the planes' points are written to 6 or more digits); its neighbours are 1000 times
    // further. A point whose shortest edge is degenerate (0) uses the plane's largest.
    const std::vector<double> edges = shortest_edges(mesh, mesh.patches[std::size_t(other.patch)]);
    double largest = 0.0;
    for (Index p : other.points)
        if (std::isfinite(edges[std::size_t(p)]))
            largest = std::max(largest, edges[std::size_t(p)]);
    const detail::UniformGrid grid(ref_positions, std::max(largest, 1e-300));
    std::vector<char> on_axis(std::size_t(mesh.n_points()), 0);
    for (Index p : other.points)
    {
        if (on_ref[std::size_t(p)])
        {
            s.axis_points.push_back(p);
            on_axis[std::size_t(p)] = 1;
            continue;
        }
        const Vector3 x = mesh.points.row(p).transpose();
        const Vector3 q = s.origin + s.to_reference * (x - s.origin);
        const double edge = edges[std::size_t(p)];
        const double tol = 1e-3 * (edge > 0.0 && std::isfinite(edge) ? edge : largest);
        Eigen::Index best = -1;
        double best_distance = tol;
        grid.for_each_within(q.x(), q.y(), q.z(), tol,
                             [&](Eigen::Index i)
                             {
                                 const double dist = (ref_positions.row(i).transpose() - q).norm();
                                 if (dist <= best_distance)
                                 {
                                     best_distance = dist;
                                     best = i;
                                 }
                             });
        s.plane_points.emplace_back(p, other.normal);
        if (best < 0)
            continue; // a lone point: it only keeps within its plane
        s.pairs.push_back(
            {ref.points[std::size_t(best)], p, s.to_reference.transpose(), ref.patch});
    }
    for (Index p : ref.points)
        if (!on_axis[std::size_t(p)])
            s.plane_points.emplace_back(p, ref.normal);
    return s;
}

} // namespace meshmorph::morph
