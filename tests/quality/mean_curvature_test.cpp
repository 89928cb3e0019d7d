// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/quality/mean_curvature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "shape_meshes.h"

using namespace meshmorph;

namespace
{

// Icosahedron subdivided `levels` times (edge midpoints), every vertex on the sphere of
// radius r.
TriangleSurface icosphere(int levels, double r)
{
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vector3> v{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                           {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                           {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    std::vector<std::array<Index, 3>> f{
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (Vector3& p : v)
        p.normalize();
    for (int level = 0; level < levels; ++level)
    {
        std::map<std::pair<Index, Index>, Index> mid;
        const auto midpoint = [&](Index a, Index b)
        {
            const std::pair<Index, Index> k{std::min(a, b), std::max(a, b)};
            const auto it = mid.find(k);
            if (it != mid.end())
                return it->second;
            v.push_back((v[a] + v[b]).normalized());
            return mid[k] = static_cast<Index>(v.size() - 1);
        };
        std::vector<std::array<Index, 3>> next;
        for (const auto& t : f)
        {
            const Index a = midpoint(t[0], t[1]);
            const Index b = midpoint(t[1], t[2]);
            const Index c = midpoint(t[2], t[0]);
            next.push_back({t[0], a, c});
            next.push_back({t[1], b, a});
            next.push_back({t[2], c, b});
            next.push_back({a, b, c});
        }
        f = next;
    }
    TriangleSurface s;
    s.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
    for (std::size_t i = 0; i < v.size(); ++i)
        s.vertices.row(i) = r * v[i].transpose();
    s.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
    for (std::size_t i = 0; i < f.size(); ++i)
        s.triangles.row(i) << f[i][0], f[i][1], f[i][2];
    return s;
}

// n x n grid of the unit square in the plane z = 0 (points jittered in-plane), 2 triangles
// per cell.
TriangleSurface plane_grid(int n, double jitter, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-jitter / n, jitter / n);
    TriangleSurface s;
    s.vertices.resize((n + 1) * (n + 1), 3);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
        {
            const bool inner = i > 0 && j > 0 && i < n && j < n;
            s.vertices.row(i + (n + 1) * j) << double(i) / n + (inner ? u(rng) : 0),
                double(j) / n + (inner ? u(rng) : 0), 0.0;
        }
    s.triangles.resize(2 * n * n, 3);
    Index t = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
            const Index a = i + (n + 1) * j;
            s.triangles.row(t++) << a, a + 1, a + n + 2;
            s.triangles.row(t++) << a, a + n + 2, a + n + 1;
        }
    return s;
}

double max_relative_error(const Eigen::VectorXd& h, double expected)
{
    double e = 0;
    for (Index i = 0; i < h.size(); ++i)
    {
        EXPECT_FALSE(std::isnan(h[i])) << "vertex " << i;
        e = std::max(e, std::abs(h[i] / expected - 1.0));
    }
    return e;
}

} // namespace

TEST(MeanCurvature, icosphere_converges_to_one_over_radius)
{
    const double r = 2.5;
    // The icosahedron is vertex-transitive, so Δx is radial, and its radial part is exact
    // (see radial_part_is_exact_for_vertices_on_a_sphere).
    EXPECT_LT(max_relative_error(mean_curvature(icosphere(0, r)), 1.0 / r), 1e-14);
    double previous = 1.0;
    for (int level = 2; level <= 5; ++level)
    {
        const double error = max_relative_error(mean_curvature(icosphere(level, r)), 1.0 / r);
        // Second order: halving the edge length divides the error by ~4; require > 3.
        EXPECT_LT(error, previous / 3.0) << "level " << level;
        previous = error;
    }
    EXPECT_LT(previous, 1e-5); // 10242 vertices
}

TEST(MeanCurvature, radial_part_is_exact_for_vertices_on_a_sphere)
{
    // With every vertex on a sphere (centre c, radius R), (x_j - x_i).(x_i - c) = -|e_ij|^2 / 2,
    // and the Voronoi area is 1/8 sum (cot a + cot b)|e_ij|^2, so Δx_i.(x_i - c)/R = -2/R
    // exactly for non-obtuse one-rings, whatever the tangential error.
    const double r = 1.7;
    TriangleSurface s = icosphere(3, r);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-0.01, 0.01);
    for (Index i = 0; i < s.n_vertices(); ++i)
    {
        const Vector3 x = s.vertices.row(i).transpose() + Vector3(u(rng), u(rng), u(rng));
        s.vertices.row(i) = r * x.normalized().transpose();
    }
    const Points lb = laplace_beltrami(s.vertices, s.triangles);
    for (Index i = 0; i < s.n_vertices(); ++i)
        EXPECT_NEAR(lb.row(i).dot(s.vertices.row(i)) / r, -2.0 / r, 1e-12) << "vertex " << i;
}

TEST(MeanCurvature, mean_curvature_normal_points_inwards_on_sphere)
{
    const TriangleSurface s = icosphere(3, 1.0);
    const Points lb = laplace_beltrami(s.vertices, s.triangles);
    for (Index i = 0; i < s.n_vertices(); ++i)
        EXPECT_LT(lb.row(i).dot(s.vertices.row(i)), 0.0) << "Δx = -2 H n with n outwards";
}

TEST(MeanCurvature, scale_invariance_of_h_times_length)
{
    const TriangleSurface s = icosphere(2, 1.0);
    const Eigen::VectorXd h = mean_curvature(s);
    for (double scale : {1e-6, 1e6})
    {
        const Points scaled = scale * s.vertices;
        const Eigen::VectorXd hs = mean_curvature(scaled, s.triangles);
        for (Index i = 0; i < h.size(); ++i)
            EXPECT_NEAR(hs[i] * scale, h[i], 1e-12 * h[i]);
    }
}

TEST(MeanCurvature, plane_is_zero_inside_and_nan_on_border)
{
    const int n = 8;
    const TriangleSurface s = plane_grid(n, 0.3, 5);
    const Eigen::VectorXd h = mean_curvature(s);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
        {
            const double value = h[i + (n + 1) * j];
            if (i == 0 || j == 0 || i == n || j == n)
                EXPECT_TRUE(std::isnan(value));
            else
                // Linear precision of the cotangent Laplacian: exactly 0 up to rounding of
                // O(1) coordinates divided by areas O(1/n^2).
                EXPECT_NEAR(value, 0.0, 1e-12);
        }
}

TEST(MeanCurvature, cube_sphere_patches_of_a_box_mesh)
{
    // Box mesh [-1,1]^3 with boundary points projected onto the sphere of radius R: the six
    // quad patches form a closed surface with every vertex on the sphere.
    const double r = 3.0;
    double previous = 1.0;
    double centre_fan_error = 0.0;
    for (int n : {4, 8, 16})
    {
        PolyMesh mesh = test::make_box_mesh(n, n, n, Vector3(-1, -1, -1), Vector3(1, 1, 1));
        const std::vector<char> on_boundary = boundary_point_mask(mesh);
        for (Index p = 0; p < mesh.n_points(); ++p)
            if (on_boundary[p])
                mesh.points.row(p) = r * mesh.points.row(p).normalized();
        const Eigen::VectorXd h = patch_mean_curvature(mesh);
        const Eigen::VectorXd h_fan = patch_mean_curvature(mesh, {}, PolygonSplit::centre_fan);
        double error = 0;
        centre_fan_error = 0;
        for (Index p = 0; p < mesh.n_points(); ++p)
        {
            if (!on_boundary[p])
            {
                EXPECT_TRUE(std::isnan(h[p]));
                continue;
            }
            ASSERT_FALSE(std::isnan(h[p])) << "point " << p;
            error = std::max(error, std::abs(h[p] * r - 1.0));
            centre_fan_error = std::max(centre_fan_error, std::abs(h_fan[p] * r - 1.0));
        }
        EXPECT_LT(error, previous / 3.0) << "second-order convergence, n = " << n;
        previous = error;
    }
    EXPECT_LT(previous, 1e-3);
    // Fan centres (vertex averages) lie inside the sphere by O(h^2): an O(1) error that does
    // not shrink, as documented for PolygonSplit::centre_fan.
    EXPECT_GT(centre_fan_error, 0.1);
}

TEST(MeanCurvature, single_flat_patch_and_box_faces)
{
    const PolyMesh mesh = test::make_box_mesh(4, 3, 2);
    const Index zmax = mesh.find_patch("zMax");
    const Eigen::VectorXd h = patch_mean_curvature(mesh, {zmax});
    const std::vector<Index> pts = patch_points(mesh, mesh.patches[zmax]);
    int inner = 0;
    for (Index p = 0; p < mesh.n_points(); ++p)
    {
        const Vector3 x = mesh.points.row(p).transpose();
        const bool on_top = std::find(pts.begin(), pts.end(), p) != pts.end();
        const bool on_rim =
            x.x() < 1e-12 || x.x() > 1 - 1e-12 || x.y() < 1e-12 || x.y() > 1 - 1e-12;
        if (!on_top || on_rim)
            EXPECT_TRUE(std::isnan(h[p])) << "point " << p;
        else
        {
            EXPECT_NEAR(h[p], 0.0, 1e-12);
            ++inner;
        }
    }
    EXPECT_EQ(inner, 3 * 2);

    // The whole closed box: flat inside each face, curved along the edges.
    const Eigen::VectorXd all = patch_mean_curvature(mesh);
    for (Index p = 0; p < mesh.n_points(); ++p)
    {
        const Vector3 x = mesh.points.row(p).transpose();
        int on_sides = 0;
        for (int k = 0; k < 3; ++k)
            on_sides += x[k] < 1e-12 || x[k] > 1 - 1e-12;
        if (on_sides == 1)
        {
            EXPECT_NEAR(all[p], 0.0, 1e-12);
        }
        else if (on_sides >= 2)
        {
            EXPECT_GT(all[p], 0.1);
        }
    }
}

TEST(MeanCurvature, open_cylinder_is_half_inverse_radius)
{
    // Cylinder of radius R, nz rings of nt points; the two end rings are border (NaN).
    const double r = 0.7;
    const int nt = 96;
    const int nz = 6;
    const double dz = 2 * M_PI * r / nt; // near-square triangles
    TriangleSurface s;
    s.vertices.resize(nt * nz, 3);
    for (int k = 0; k < nz; ++k)
        for (int i = 0; i < nt; ++i)
        {
            const double a = 2 * M_PI * i / nt + (k % 2) * M_PI / nt; // staggered rings
            s.vertices.row(i + nt * k) << r * std::cos(a), r * std::sin(a), k * dz;
        }
    s.triangles.resize(2 * nt * (nz - 1), 3);
    Index t = 0;
    for (int k = 0; k + 1 < nz; ++k)
        for (int i = 0; i < nt; ++i)
        {
            const Index a = i + nt * k, b = (i + 1) % nt + nt * k;
            const Index c = i + nt * (k + 1), d = (i + 1) % nt + nt * (k + 1);
            if (k % 2 == 0)
            {
                s.triangles.row(t++) << a, b, c;
                s.triangles.row(t++) << b, d, c;
            }
            else
            {
                s.triangles.row(t++) << a, d, c;
                s.triangles.row(t++) << a, b, d;
            }
        }
    const Eigen::VectorXd h = mean_curvature(s);
    for (int k = 0; k < nz; ++k)
        for (int i = 0; i < nt; ++i)
        {
            const double value = h[i + nt * k];
            if (k == 0 || k == nz - 1)
                EXPECT_TRUE(std::isnan(value));
            else
                // Chord-vs-arc discretisation error ~ (pi/nt)^2 ~ 1e-3 relative.
                EXPECT_NEAR(value * 2 * r, 1.0, 5e-3) << "ring " << k;
        }
}

TEST(MeanCurvature, bad_labels_throw)
{
    TriangleSurface s = plane_grid(2, 0, 1);
    s.triangles(1, 2) = 99;
    EXPECT_THROW(mean_curvature(s), InvalidInput);
    s.triangles(1, 2) = -1;
    EXPECT_THROW(mean_curvature(s), InvalidInput);
    const PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    EXPECT_THROW(patch_mean_curvature(mesh, {17}), InvalidInput);
}

TEST(MeanCurvature, triangulate_patches_splits_polygons_without_new_vertices_when_convex)
{
    // Pentagon cells: every boundary face is convex: n - 2 triangles each, no centres.
    const PolyMesh mesh = test::make_pentagon_cells();
    const TriangleSurface s = triangulate_patches(mesh);
    Index expected = 0;
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
        expected += mesh.faces.item_size(f) - 2;
    EXPECT_EQ(s.n_triangles(), expected);
    EXPECT_EQ(s.n_vertices(), mesh.n_points());
    // Orientation and area are preserved: summed triangle area vectors = face area vectors.
    Vector3 total = Vector3::Zero();
    for (Index t = 0; t < s.n_triangles(); ++t)
    {
        const Vector3 a = s.vertices.row(s.triangles(t, 0)).transpose();
        const Vector3 b = s.vertices.row(s.triangles(t, 1)).transpose();
        const Vector3 c = s.vertices.row(s.triangles(t, 2)).transpose();
        total += 0.5 * (b - a).cross(c - a);
    }
    EXPECT_NEAR(total.norm(), 0.0, 1e-14) << "closed surface";

    // A U-shaped octagon has no vertex seeing all others: centre vertex and 8-triangle fan.
    // (An L-shape would be fanned from a vertex that sees the whole polygon.)
    PolyMesh u_shape;
    u_shape.points.resize(8, 3);
    u_shape.points << 0, 0, 0, 3, 0, 0, 3, 2, 0, 2, 2, 0, 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0;
    u_shape.faces.push_back({0, 1, 2, 3, 4, 5, 6, 7});
    u_shape.owner.push_back(0);
    u_shape.patches.push_back({"p", "patch", 0, 1, {}, {}});
    u_shape.finalize();
    const TriangleSurface us = triangulate_patches(u_shape);
    EXPECT_EQ(us.n_vertices(), 9);
    EXPECT_EQ(us.n_triangles(), 8);

    PolyMesh l_shape = u_shape;
    l_shape.points.resize(6, 3);
    l_shape.points << 0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0;
    l_shape.faces.clear();
    l_shape.faces.push_back({2, 3, 4, 5, 0, 1}); // the fan from (2 1 0) would be flipped
    const TriangleSurface ls = triangulate_patches(l_shape);
    EXPECT_EQ(ls.n_vertices(), 6);
    EXPECT_EQ(ls.n_triangles(), 4);
}
