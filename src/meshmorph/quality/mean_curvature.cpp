// SPDX-License-Identifier: GPL-3.0-or-later
// Cotangent Laplace-Beltrami and mixed Voronoi areas (Meyer et al. 2003).
#include "meshmorph/quality/mean_curvature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/quality/mesh_edges.h"

namespace meshmorph
{
namespace
{

void check_labels(Index n_vertices, const Triangles& triangles)
{
    for (Index t = 0; t < triangles.rows(); ++t)
        for (int k = 0; k < 3; ++k)
            if (triangles(t, k) < 0 || triangles(t, k) >= n_vertices)
                throw InvalidInput("triangle " + std::to_string(t) + " has vertex label " +
                                   std::to_string(triangles(t, k)) + " outside [0, " +
                                   std::to_string(n_vertices) + ")");
}

// Vertices on an edge used by exactly one triangle.
std::vector<char> border_vertices(Index n_vertices, const Triangles& triangles)
{
    std::unordered_map<std::uint64_t, int> edge_count;
    edge_count.reserve(static_cast<std::size_t>(triangles.rows()) * 3);
    for (Index t = 0; t < triangles.rows(); ++t)
        for (int k = 0; k < 3; ++k)
            ++edge_count[packed_edge(triangles(t, k), triangles(t, (k + 1) % 3))];
    std::vector<char> border(static_cast<std::size_t>(n_vertices), 0);
    for (const auto& [k, count] : edge_count)
        if (count == 1)
        {
            border[k & 0xffffffffu] = 1;
            border[k >> 32] = 1;
        }
    return border;
}

} // namespace

Points laplace_beltrami(const Eigen::Ref<const Points>& vertices, const Triangles& triangles)
{
    const Index n = static_cast<Index>(vertices.rows());
    check_labels(n, triangles);
    Points sum = Points::Zero(n, 3);
    Eigen::VectorXd area = Eigen::VectorXd::Zero(n);
    std::vector<char> used(static_cast<std::size_t>(n), 0);

    for (Index t = 0; t < triangles.rows(); ++t)
    {
        const Index v[3] = {triangles(t, 0), triangles(t, 1), triangles(t, 2)};
        const Vector3 p[3] = {vertices.row(v[0]).transpose(), vertices.row(v[1]).transpose(),
                              vertices.row(v[2]).transpose()};
        for (int k = 0; k < 3; ++k)
            used[v[k]] = 1;
        const double double_area = (p[1] - p[0]).cross(p[2] - p[0]).norm();
        if (!(double_area > 0.0))
            continue; // degenerate: cotangents undefined
        double cot[3];
        double dot[3];
        for (int k = 0; k < 3; ++k)
        {
            const Vector3 a = p[(k + 1) % 3] - p[k];
            const Vector3 b = p[(k + 2) % 3] - p[k];
            dot[k] = a.dot(b);
            // |a x b| is twice the triangle area at every corner.
            cot[k] = dot[k] / double_area;
        }
        for (int k = 0; k < 3; ++k)
        {
            // Corner k weights the opposite edge (i, j).
            const int i = (k + 1) % 3;
            const int j = (k + 2) % 3;
            const Vector3 e = p[j] - p[i];
            sum.row(v[i]) += cot[k] * e.transpose();
            sum.row(v[j]) -= cot[k] * e.transpose();
        }
        // Mixed area (Meyer et al., Fig. 4).
        const double tri_area = 0.5 * double_area;
        const bool obtuse = dot[0] < 0 || dot[1] < 0 || dot[2] < 0;
        for (int k = 0; k < 3; ++k)
        {
            if (!obtuse)
            {
                // Voronoi: 1/8 (|e_ki|^2 cot(angle at j) + |e_kj|^2 cot(angle at i)).
                const int i = (k + 1) % 3;
                const int j = (k + 2) % 3;
                area[v[k]] += 0.125 * ((p[i] - p[k]).squaredNorm() * cot[j] +
                                       (p[j] - p[k]).squaredNorm() * cot[i]);
            }
            else
                area[v[k]] += dot[k] < 0 ? 0.5 * tri_area : 0.25 * tri_area;
        }
    }

    const std::vector<char> border = border_vertices(n, triangles);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (Index i = 0; i < n; ++i)
    {
        if (!used[i] || border[i] || !(area[i] > 0.0))
            sum.row(i).setConstant(nan);
        else
            sum.row(i) /= 2.0 * area[i];
    }
    return sum;
}

Eigen::VectorXd mean_curvature(const Eigen::Ref<const Points>& vertices, const Triangles& triangles)
{
    const Points lb = laplace_beltrami(vertices, triangles);
    return 0.5 * lb.rowwise().norm();
}

Eigen::VectorXd mean_curvature(const TriangleSurface& surface)
{
    return mean_curvature(surface.vertices, surface.triangles);
}

namespace
{

//! The patches to triangulate (all when `patches` is empty), checked against the mesh.
std::vector<Index> selected_patches(const PolyMesh& mesh, const std::vector<Index>& patches)
{
    std::vector<Index> selected = patches;
    if (selected.empty())
        for (Index p = 0; p < static_cast<Index>(mesh.patches.size()); ++p)
            selected.push_back(p);
    for (Index p : selected)
    {
        if (p < 0 || p >= static_cast<Index>(mesh.patches.size()))
            throw InvalidInput("triangulate_patches: patch index " + std::to_string(p) +
                               " out of range [0, " + std::to_string(mesh.patches.size()) + ")");
        const Patch& patch = mesh.patches[p];
        if (patch.start_face < 0 || patch.n_faces < 0 ||
            patch.start_face + patch.n_faces > mesh.n_faces())
            throw InvalidInput("triangulate_patches: patch '" + patch.name +
                               "' has faces outside the mesh");
    }
    return selected;
}

//! Triangles of the faces of a polyMesh boundary, with extra centre vertices after the mesh
//! points where a face is fanned from its centre.
class PatchTriangulator
{
public:
    PatchTriangulator(const PolyMesh& mesh, PolygonSplit split) : mesh_(mesh), split_(split) {}

    void add_face(Index f)
    {
        const std::span<const Index> face = mesh_.faces[f];
        check_face(f, face);
        if (face.size() == 3)
            triangles_.push_back({face[0], face[1], face[2]});
        else if (split_ == PolygonSplit::diagonals && face.size() == 4)
            add_quad(face);
        else if (!(split_ == PolygonSplit::diagonals && add_vertex_fan(face)))
            add_centre_fan(face);
    }

    TriangleSurface surface() const
    {
        const Index n_points = mesh_.n_points();
        TriangleSurface surface;
        surface.vertices.resize(n_points + static_cast<Index>(centres_.size()), 3);
        surface.vertices.topRows(n_points) = mesh_.points;
        for (std::size_t i = 0; i < centres_.size(); ++i)
            surface.vertices.row(n_points + static_cast<Index>(i)) = centres_[i].transpose();
        surface.triangles.resize(static_cast<Index>(triangles_.size()), 3);
        for (std::size_t t = 0; t < triangles_.size(); ++t)
            surface.triangles.row(static_cast<Index>(t)) << triangles_[t][0], triangles_[t][1],
                triangles_[t][2];
        return surface;
    }

private:
    Vector3 point(Index v) const { return mesh_.points.row(v).transpose(); }

    void check_face(Index f, std::span<const Index> face) const
    {
        if (face.size() < 3)
            throw InvalidInput("triangulate_patches: face " + std::to_string(f) + " has " +
                               std::to_string(face.size()) + " vertices");
        for (Index v : face)
            if (v < 0 || v >= mesh_.n_points())
                throw InvalidInput("triangulate_patches: face " + std::to_string(f) +
                                   " has point label " + std::to_string(v) + " outside [0, " +
                                   std::to_string(mesh_.n_points()) + ")");
    }

    //! Split along the shorter diagonal.
    void add_quad(std::span<const Index> face)
    {
        if ((point(face[2]) - point(face[0])).squaredNorm() <=
            (point(face[3]) - point(face[1])).squaredNorm())
        {
            triangles_.push_back({face[0], face[1], face[2]});
            triangles_.push_back({face[0], face[2], face[3]});
        }
        else
        {
            triangles_.push_back({face[1], face[2], face[3]});
            triangles_.push_back({face[1], face[3], face[0]});
        }
    }

    Vector3 centre(std::span<const Index> face) const
    {
        Vector3 c = Vector3::Zero();
        for (Index v : face)
            c += point(v);
        c /= static_cast<double>(face.size());
        return c;
    }

    //! Fan from the first vertex whose fan triangles all agree with the face's orientation
    //! (strictly: collinear vertices would give zero-area triangles). False if there is none.
    bool add_vertex_fan(std::span<const Index> face)
    {
        const std::size_t n = face.size();
        const Vector3 c = centre(face);
        Vector3 normal = Vector3::Zero();
        for (std::size_t i = 0; i < n; ++i)
            normal += (point(face[i]) - c).cross(point(face[(i + 1) % n]) - c);
        for (std::size_t s0 = 0; s0 < n; ++s0)
        {
            const Vector3 apex = point(face[s0]);
            bool ok = true;
            for (std::size_t i = 1; i + 1 < n && ok; ++i)
                ok = (point(face[(s0 + i) % n]) - apex)
                         .cross(point(face[(s0 + i + 1) % n]) - apex)
                         .dot(normal) > 0.0;
            if (!ok)
                continue;
            for (std::size_t i = 1; i + 1 < n; ++i)
                triangles_.push_back({face[s0], face[(s0 + i) % n], face[(s0 + i + 1) % n]});
            return true;
        }
        return false;
    }

    void add_centre_fan(std::span<const Index> face)
    {
        const Index c = mesh_.n_points() + static_cast<Index>(centres_.size());
        centres_.push_back(centre(face));
        for (std::size_t i = 0; i < face.size(); ++i)
            triangles_.push_back({face[i], face[(i + 1) % face.size()], c});
    }

    const PolyMesh& mesh_;
    PolygonSplit split_;
    std::vector<std::array<Index, 3>> triangles_;
    std::vector<Vector3> centres_;
};

} // namespace

TriangleSurface triangulate_patches(const PolyMesh& mesh, const std::vector<Index>& patches,
                                    PolygonSplit split)
{
    const std::vector<Index> selected = selected_patches(mesh, patches);
    PatchTriangulator triangulator(mesh, split);
    for (Index p : selected)
    {
        const Patch& patch = mesh.patches[p];
        for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
            triangulator.add_face(f);
    }
    return triangulator.surface();
}

Eigen::VectorXd patch_mean_curvature(const PolyMesh& mesh, const std::vector<Index>& patches,
                                     PolygonSplit split)
{
    const TriangleSurface surface = triangulate_patches(mesh, patches, split);
    const Eigen::VectorXd h = mean_curvature(surface);
    return h.head(mesh.n_points());
}

} // namespace meshmorph
