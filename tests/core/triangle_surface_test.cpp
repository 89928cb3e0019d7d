// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of core/triangle_surface.h: closest points on triangles and the AABB tree (the
// STL/OBJ readers are tested in tests/io/surface_io_test.cpp).
#include "meshmorph/core/triangle_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "meshmorph/core/exceptions.h"

using namespace meshmorph;

namespace
{

// A bumpy closed sphere: UV grid with radial noise.
TriangleSurface bumpy_sphere(int nu, int nv, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.9, 1.1);
    TriangleSurface s;
    s.vertices.resize(2 + nu * (nv - 1), 3);
    s.vertices.row(0) << 0, 0, 1;
    s.vertices.row(1) << 0, 0, -1;
    for (int j = 1; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
        {
            const double th = M_PI * j / nv, ph = 2 * M_PI * i / nu, r = u(rng);
            s.vertices.row(2 + i + nu * (j - 1)) << r * std::sin(th) * std::cos(ph),
                r * std::sin(th) * std::sin(ph), r * std::cos(th);
        }
    std::vector<std::array<Index, 3>> t;
    const auto id = [&](int i, int j) { return Index(2 + (i % nu) + nu * (j - 1)); };
    for (int i = 0; i < nu; ++i)
    {
        t.push_back({0, id(i, 1), id(i + 1, 1)});
        t.push_back({1, id(i + 1, nv - 1), id(i, nv - 1)});
        for (int j = 1; j + 1 < nv; ++j)
        {
            t.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
            t.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
        }
    }
    s.triangles.resize(static_cast<Eigen::Index>(t.size()), 3);
    for (std::size_t k = 0; k < t.size(); ++k)
        s.triangles.row(static_cast<Eigen::Index>(k)) << t[k][0], t[k][1], t[k][2];
    return s;
}

} // namespace

TEST(TriangleSurface, closest_point_on_triangle_regions)
{
    const Vector3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
    EXPECT_EQ(closest_point_on_triangle(Vector3(0.5, 0.5, 3), a, b, c), Vector3(0.5, 0.5, 0));
    EXPECT_EQ(closest_point_on_triangle(Vector3(-1, -1, 1), a, b, c), a);
    EXPECT_EQ(closest_point_on_triangle(Vector3(5, -1, 0), a, b, c), b);
    EXPECT_EQ(closest_point_on_triangle(Vector3(1, -3, 1), a, b, c), Vector3(1, 0, 0));
    EXPECT_TRUE(closest_point_on_triangle(Vector3(2, 2, 0), a, b, c).isApprox(Vector3(1, 1, 0)));
    // Degenerate (collinear) triangle: the closest point of its segments, never NaN.
    const Vector3 p = closest_point_on_triangle(Vector3(1, 1, 0), a, b, Vector3(1, 0, 0));
    EXPECT_EQ(p, Vector3(1, 0, 0));
}

TEST(TriangleSurface, tree_matches_brute_force)
{
    const TriangleSurface s = bumpy_sphere(24, 16, 3);
    const SurfaceTree tree(s);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-3, 3);
    Points queries(400, 3);
    for (Index q = 0; q < queries.rows(); ++q)
        queries.row(q) << u(rng), u(rng), u(rng);
    queries.row(0) << 0, 0, 0;
    queries.row(1) << 100, -50, 7;
    const Points batch = tree.closest_points(queries);
    for (Index q = 0; q < queries.rows(); ++q)
    {
        const Vector3 x = queries.row(q).transpose();
        double best = std::numeric_limits<double>::infinity();
        for (Index t = 0; t < s.n_triangles(); ++t)
            best = std::min(
                best, (closest_point_on_triangle(x, s.vertices.row(s.triangles(t, 0)).transpose(),
                                                 s.vertices.row(s.triangles(t, 1)).transpose(),
                                                 s.vertices.row(s.triangles(t, 2)).transpose()) -
                       x)
                          .norm());
        const SurfacePoint sp = tree.closest_point(x);
        // The nearest distance, or one tied with it (the tie rule may pick a triangle
        // whose distance differs from the smallest only by round-off).
        EXPECT_GE(sp.distance, best) << "query " << q;
        EXPECT_LE(sp.distance, best + tree.tie_tolerance()) << "query " << q;
        EXPECT_NEAR((sp.point - x).norm(), sp.distance, 1e-15 * (1 + sp.distance));
        EXPECT_TRUE(Vector3(batch.row(q)).isApprox(sp.point, 1e-15) ||
                    (Vector3(batch.row(q)) - sp.point).norm() < 1e-15);
    }
    // Vertices are on the surface.
    for (Index v = 0; v < s.n_vertices(); ++v)
        EXPECT_EQ(tree.closest_point(s.vertices.row(v).transpose()).distance, 0.0);
}

// A roof: two slopes meeting at a ridge along y (x = 0, z = 1), symmetric about x = 0.
// Slope triangles are listed in the order given (the tie rule picks the first listed).
TriangleSurface roof(bool left_first)
{
    TriangleSurface s;
    s.vertices.resize(6, 3);
    s.vertices << -1, -1, 0, -1, 1, 0, 0, -1, 1, 0, 1, 1, 1, -1, 0, 1, 1, 0;
    const Eigen::Matrix<Index, 2, 3, Eigen::RowMajor> left{{0, 2, 3}, {0, 3, 1}};
    const Eigen::Matrix<Index, 2, 3, Eigen::RowMajor> right{{2, 4, 5}, {2, 5, 3}};
    s.triangles.resize(4, 3);
    s.triangles.topRows(2) = left_first ? left : right;
    s.triangles.bottomRows(2) = left_first ? right : left;
    return s;
}

TEST(TriangleSurface, a_point_equally_near_two_slopes_goes_to_the_slope_listed_first)
{
    // Below the ridge, on the plane of symmetry: both slopes are at the same distance, and
    // which one wins must not depend on the last bits of the arithmetic. Offsets of 1e-15
    // (round-off) keep the rule's choice; an offset of 1e-6 (geometry) picks the nearer.
    for (const bool left_first : {true, false})
    {
        const SurfaceTree tree(roof(left_first));
        const double side = left_first ? -1.0 : 1.0;
        for (const double dx : {0.0, 1e-15, -1e-15, 3e-16})
        {
            for (const double y : {-0.5, 0.0, 0.25})
            {
                const SurfacePoint p = tree.closest_point(Vector3(dx, y, 0.2));
                EXPECT_LE(p.triangle, 1) << "dx " << dx << " y " << y;
                EXPECT_NEAR(p.point.x(), side * 0.4, 1e-12) << "dx " << dx << " y " << y;
            }
        }
        const SurfacePoint nearer_right = tree.closest_point(Vector3(1e-6, 0.0, 0.2));
        EXPECT_GT(nearer_right.point.x(), 0.0);
        const SurfacePoint nearer_left = tree.closest_point(Vector3(-1e-6, 0.0, 0.2));
        EXPECT_LT(nearer_left.point.x(), 0.0);
    }
}

TEST(TriangleSurface, a_point_near_a_shared_edge_gets_its_exact_foot_not_the_edge)
{
    // A flat square of two triangles sharing the diagonal x = y; the one listed first is
    // below it. A query above the second one, its foot 1e-5 from the diagonal: the first
    // triangle's closest point (on the diagonal) is only e^2 / 2d = 1.5e-10 farther, inside
    // the tie band, but it is the same place, and the exact foot must be returned.
    TriangleSurface s;
    s.vertices.resize(4, 3);
    s.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
    s.triangles.resize(2, 3);
    s.triangles << 0, 1, 2, 0, 2, 3; // first: below the diagonal (x > y)
    const SurfaceTree tree(s);
    const double e = 1e-5 / std::sqrt(2.0);
    const Vector3 query(0.5 - e, 0.5 + e, 0.33);
    const SurfacePoint p = tree.closest_point(query);
    EXPECT_EQ(p.triangle, 1);
    EXPECT_LE((p.point - Vector3(0.5 - e, 0.5 + e, 0.0)).norm(), 1e-15);
    EXPECT_NEAR(p.distance, 0.33, 1e-15);
}

TEST(TriangleSurface, tree_rejects_bad_surfaces)
{
    EXPECT_THROW(SurfaceTree(TriangleSurface{}), InvalidInput);
    TriangleSurface s = bumpy_sphere(6, 4, 1);
    s.triangles(2, 1) = s.n_vertices();
    EXPECT_THROW(SurfaceTree{s}, InvalidInput);
    s = bumpy_sphere(6, 4, 1);
    s.vertices(3, 0) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(SurfaceTree{s}, InvalidInput);
}
