// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/quality/scaled_jacobian.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/quality/check_mesh.h"
#include "shape_meshes.h"

#if MESHMORPH_TEST_WITH_VTK
#include <vtkHexahedron.h>
#include <vtkMeshQuality.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkTetra.h>
#endif

using namespace meshmorph;

namespace
{

// Block mesh with interior points jittered by up to `amount` of the cell size.
PolyMesh jittered_block(int n, double amount, unsigned seed)
{
    PolyMesh mesh = test::make_box_mesh(n, n, n);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-amount / n, amount / n);
    const std::vector<char> boundary = boundary_point_mask(mesh);
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (!boundary[p])
            mesh.points.row(p) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
    return mesh;
}

std::array<Vector3, 4> regular_tet(double a)
{
    // Vertices of a regular tetrahedron with edge a; (0, 1, 2) counter-clockwise from 3.
    return {Vector3(0, 0, 0), Vector3(a, 0, 0), Vector3(a / 2, a * std::sqrt(3.0) / 2, 0),
            Vector3(a / 2, a * std::sqrt(3.0) / 6, a * std::sqrt(2.0 / 3.0))};
}

//! The corners of hexahedron c in VTK order, for the per-cell formula.
std::array<Vector3, 8> hex_corners(const PolyMesh& mesh, const CompactList& cf,
                                   const std::vector<CellShape>& shapes, Index c)
{
    const VtkCell cell = vtk_cell(mesh, cf, c, shapes[c]);
    std::array<Vector3, 8> p;
    for (int i = 0; i < 8; ++i)
        p[i] = mesh.points.row(cell.points[i]).transpose();
    return p;
}

} // namespace

TEST(ScaledJacobian, boxes_are_one_at_any_scale_and_aspect)
{
    for (double scale : {1e-6, 1.0, 1e6})
    {
        const PolyMesh mesh =
            test::make_box_mesh(3, 2, 5, Vector3(0, 0, 0), Vector3(3 * scale, 0.1 * scale, scale));
        const Eigen::VectorXd sj = scaled_jacobian(mesh);
        ASSERT_EQ(sj.size(), mesh.n_cells);
        for (Index c = 0; c < mesh.n_cells; ++c)
            EXPECT_NEAR(sj[c], 1.0, 1e-14) << "scale " << scale;
    }
}

TEST(ScaledJacobian, mirrored_mesh_is_inverted)
{
    PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    mesh.points.col(2) *= -1.0; // topology unchanged, every cell turned inside out
    const Eigen::VectorXd sj = scaled_jacobian(mesh);
    for (Index c = 0; c < mesh.n_cells; ++c)
        EXPECT_NEAR(sj[c], -1.0, 1e-14);
}

TEST(ScaledJacobian, regular_tet_is_one_and_scale_free)
{
    for (double a : {1e-5, 1.0, 1e5})
        EXPECT_NEAR(tet_scaled_jacobian(regular_tet(a)), 1.0, 1e-14);
    std::array<Vector3, 4> flipped = regular_tet(1.0);
    std::swap(flipped[1], flipped[2]);
    EXPECT_NEAR(tet_scaled_jacobian(flipped), -1.0, 1e-14);
    // Flat tet: zero.
    std::array<Vector3, 4> flat = regular_tet(1.0);
    flat[3].z() = 0;
    EXPECT_NEAR(tet_scaled_jacobian(flat), 0.0, 1e-15);
}

TEST(ScaledJacobian, kuhn_tets_prism_and_pyramid_values_derived_by_hand)
{
    // Kuhn tets of the unit cube, e.g. (0,0,0) (1,0,0) (1,1,0) (1,1,1): 6V = 1; the edge
    // length products are sqrt(2) at the middle vertices and 1*sqrt(2)*sqrt(3) = sqrt(6) at
    // the ends of the cube diagonal, so sqrt(2) * 1 / sqrt(6).
    const Eigen::VectorXd tets = scaled_jacobian(test::make_tet_cube());
    for (Index c = 0; c < tets.size(); ++c)
        EXPECT_NEAR(tets[c], std::sqrt(2.0) / std::sqrt(6.0), 1e-14);

    // Half-cube prisms: the 45 degree corners give sin 45 * 2/sqrt(3) = sqrt(2/3).
    const Eigen::VectorXd prisms = scaled_jacobian(test::make_prism_cube());
    for (Index c = 0; c < prisms.size(); ++c)
        EXPECT_NEAR(prisms[c], std::sqrt(2.0 / 3.0), 1e-14);

    // Cube-centre pyramids: base corner edges (1,0,0), (0,1,0), (1/2,1/2,1/2):
    // det = 1/2, |apex edge| = sqrt(3)/2, so sqrt(2) / sqrt(3).
    const Eigen::VectorXd pyramids = scaled_jacobian(test::make_pyramid_cube());
    for (Index c = 0; c < pyramids.size(); ++c)
        EXPECT_NEAR(pyramids[c], std::sqrt(2.0 / 3.0), 1e-14);
}

TEST(ScaledJacobian, ideal_prism_and_pyramid_are_one)
{
    const double h = std::sqrt(3.0) / 2;
    // VTK wedge order: first triangle wound away from the second (clockwise seen from above).
    const std::array<Vector3, 6> prism{Vector3(0, 0, 0), Vector3(0.5, h, 0), Vector3(1, 0, 0),
                                       Vector3(0, 0, 1), Vector3(0.5, h, 1), Vector3(1, 0, 1)};
    EXPECT_NEAR(prism_scaled_jacobian(prism), 1.0, 1e-14);
    const std::array<Vector3, 5> pyramid{Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 1, 0),
                                         Vector3(0, 1, 0), Vector3(0.5, 0.5, 1 / std::sqrt(2.0))};
    EXPECT_NEAR(pyramid_scaled_jacobian(pyramid), 1.0, 1e-14);
    std::array<Vector3, 5> inverted = pyramid;
    inverted[4].z() *= -1;
    EXPECT_NEAR(pyramid_scaled_jacobian(inverted), -1.0, 1e-14);
}

TEST(ScaledJacobian, undefined_for_wedges_and_polyhedra)
{
    const Eigen::VectorXd w = scaled_jacobian(test::make_wedge_on_hex());
    EXPECT_NEAR(w[0], 1.0, 1e-14); // the hex below
    EXPECT_TRUE(std::isnan(w[1]));
    const Eigen::VectorXd p = scaled_jacobian(test::make_pentagon_cells());
    EXPECT_TRUE(std::isnan(p[0]) && std::isnan(p[1]));
    const PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    const CompactList cf = cell_faces(mesh);
    EXPECT_THROW(scaled_jacobian(mesh, cf, {}), InvalidInput);
}

TEST(ScaledJacobian, jitter_lowers_quality_below_one)
{
    const Eigen::VectorXd sj = scaled_jacobian(jittered_block(4, 0.3, 7));
    // std:: reductions: GCC 12 warns (-Wmaybe-uninitialized) inside Eigen's AVX-512 minCoeff.
    const double lowest = *std::min_element(sj.data(), sj.data() + sj.size());
    const double highest = *std::max_element(sj.data(), sj.data() + sj.size());
    EXPECT_LT(lowest, 0.99);
    EXPECT_GT(lowest, 0.0); // 30 % jitter keeps cells valid
    EXPECT_LE(highest, 1.0 + 1e-14);
}

TEST(ScaledJacobian, threaded_path_equals_per_cell_formula)
{
    // 22500 cells: above the threshold where scaled_jacobian runs OpenMP threads.
    PolyMesh mesh = test::make_box_mesh(30, 30, 25);
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(-0.01, 0.01);
    const std::vector<char> boundary = boundary_point_mask(mesh);
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (!boundary[p])
            mesh.points.row(p) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
    const CompactList cf = cell_faces(mesh);
    const std::vector<CellShape> shapes = classify_cells(mesh, cf);
    const Eigen::VectorXd sj = scaled_jacobian(mesh, cf, shapes);
    ASSERT_EQ(sj.size(), mesh.n_cells);
    for (Index c = 0; c < mesh.n_cells; ++c)
    {
        ASSERT_EQ(sj[c], hex_scaled_jacobian(hex_corners(mesh, cf, shapes, c)))
            << "cell " << c; // bit-identical
    }
}

TEST(ScaledJacobian,
     hexahedra_taken_eight_at_once_keep_the_per_cell_bits_when_degenerate_or_inverted)
{
    // 7 x 5 x 3 = 105 hexahedra: thirteen passes of eight and one left over, serial. Some
    // cells get a zero-length edge (a point moved onto its neighbour: value 0), some are
    // inverted (a point pushed through the opposite face), the rest are jittered.
    PolyMesh mesh = test::make_box_mesh(7, 5, 3);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-0.02, 0.02);
    const std::vector<char> boundary = boundary_point_mask(mesh);
    std::vector<Index> interior;
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (!boundary[p])
        {
            interior.push_back(p);
            mesh.points.row(p) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
        }
    ASSERT_GE(interior.size(), 4u);
    mesh.points.row(interior[0]) = mesh.points.row(interior[1]);       // a zero-length edge
    mesh.points.row(interior[3]) += Eigen::RowVector3d(0.0, 0.0, 0.9); // inverted cells
    const CompactList cf = cell_faces(mesh);
    const std::vector<CellShape> shapes = classify_cells(mesh, cf);
    const Eigen::VectorXd sj = scaled_jacobian(mesh, cf, shapes);
    Index zero = 0, negative = 0;
    for (Index c = 0; c < mesh.n_cells; ++c)
    {
        ASSERT_EQ(sj[c], hex_scaled_jacobian(hex_corners(mesh, cf, shapes, c)))
            << "cell " << c; // bit-identical
        zero += sj[c] == 0.0;
        negative += sj[c] < 0.0;
    }
    EXPECT_GT(zero, 0);     // the collapsed edge's cells
    EXPECT_GT(negative, 0); // the inverted ones
}

TEST(ScaledJacobian, a_check_after_the_points_moved_reuses_the_corners_and_matches_a_fresh_one)
{
    PolyMesh mesh = jittered_block(5, 0.2, 3);
    const CompactList cf = cell_faces(mesh);
    const QualityReport before = check_mesh(mesh, cf, compute_geometry(mesh, cf), {});
    ASSERT_TRUE(before.jacobian_corners);
    mesh.points = jittered_block(5, 0.45, 11).points; // the same cells, other points
    CheckMeshSettings after_settings;
    after_settings.unchanged_topology = &before;
    const MeshGeometry g = compute_geometry(mesh, cf);
    const QualityReport after = check_mesh(mesh, cf, g, after_settings);
    const QualityReport fresh = check_mesh(mesh, cf, g, {});
    EXPECT_EQ(after.jacobian_corners, before.jacobian_corners); // shared, not recomputed
    ASSERT_EQ(after.cell_scaled_jacobian.size(), fresh.cell_scaled_jacobian.size());
    for (Index c = 0; c < mesh.n_cells; ++c)
        ASSERT_EQ(after.cell_scaled_jacobian[c], fresh.cell_scaled_jacobian[c]) << "cell " << c;
    EXPECT_NE(fresh.min_scaled_jacobian, before.min_scaled_jacobian); // the points did move
    EXPECT_EQ(after.min_scaled_jacobian, fresh.min_scaled_jacobian);
}

TEST(ScaledJacobian, corners_of_another_mesh_are_refused_or_not_reused)
{
    const PolyMesh small = jittered_block(3, 0.2, 5);
    const PolyMesh large = jittered_block(4, 0.2, 5);
    const CompactList cf_small = cell_faces(small);
    const JacobianCorners corners =
        jacobian_corners(small, cf_small, classify_cells(small, cf_small));
    EXPECT_THROW(scaled_jacobian(large, corners), InvalidInput);
    // A check "before" of another mesh: its corners are not taken, the values are right.
    const QualityReport other = check_mesh(small, cf_small, compute_geometry(small, cf_small), {});
    const CompactList cf = cell_faces(large);
    CheckMeshSettings settings;
    settings.unchanged_topology = &other;
    const QualityReport r = check_mesh(large, cf, compute_geometry(large, cf), settings);
    EXPECT_NE(r.jacobian_corners, other.jacobian_corners);
    const Eigen::VectorXd expected = scaled_jacobian(large);
    for (Index c = 0; c < large.n_cells; ++c)
        ASSERT_EQ(r.cell_scaled_jacobian[c], expected[c]) << "cell " << c;
}

#if MESHMORPH_TEST_WITH_VTK
TEST(ScaledJacobian, hexes_match_vtk_mesh_quality)
{
    // Heavy jitter (70 % of the cell size) also produces inverted and non-convex hexes.
    for (double amount : {0.2, 0.7})
    {
        const PolyMesh mesh = jittered_block(5, amount, 11);
        const CompactList cf = cell_faces(mesh);
        const std::vector<CellShape> shapes = classify_cells(mesh, cf);
        const Eigen::VectorXd sj = scaled_jacobian(mesh, cf, shapes);
        int negative = 0;
        for (Index c = 0; c < mesh.n_cells; ++c)
        {
            const VtkCell cell = vtk_cell(mesh, cf, c, shapes[c]);
            ASSERT_EQ(cell.type, VtkCellType::hexahedron);
            vtkNew<vtkHexahedron> hex;
            for (int i = 0; i < 8; ++i)
            {
                hex->GetPointIds()->SetId(i, i);
                hex->GetPoints()->SetPoint(i, mesh.points(cell.points[i], 0),
                                           mesh.points(cell.points[i], 1),
                                           mesh.points(cell.points[i], 2));
            }
            const double expected = vtkMeshQuality::HexScaledJacobian(hex);
            // Same formula, different summation order of the centre axes: rounding only.
            EXPECT_NEAR(sj[c], expected, 1e-13) << "cell " << c;
            negative += sj[c] < 0;
        }
        if (amount > 0.5)
        {
            EXPECT_GT(negative, 0) << "the heavy-jitter case should contain inverted cells";
        }
    }
}

TEST(ScaledJacobian, tets_match_vtk_mesh_quality)
{
    PolyMesh mesh = test::make_tet_cube();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    for (int trial = 0; trial < 20; ++trial)
    {
        for (Index p = 0; p < mesh.n_points(); ++p)
            mesh.points.row(p) =
                test::cube_points().row(p) + Eigen::RowVector3d(u(rng), u(rng), u(rng));
        const CompactList cf = cell_faces(mesh);
        const std::vector<CellShape> shapes = classify_cells(mesh, cf);
        const Eigen::VectorXd sj = scaled_jacobian(mesh, cf, shapes);
        for (Index c = 0; c < mesh.n_cells; ++c)
        {
            const VtkCell cell = vtk_cell(mesh, cf, c, shapes[c]);
            ASSERT_EQ(cell.type, VtkCellType::tetra);
            vtkNew<vtkTetra> tet;
            for (int i = 0; i < 4; ++i)
            {
                tet->GetPointIds()->SetId(i, i);
                tet->GetPoints()->SetPoint(i, mesh.points(cell.points[i], 0),
                                           mesh.points(cell.points[i], 1),
                                           mesh.points(cell.points[i], 2));
            }
            EXPECT_NEAR(sj[c], vtkMeshQuality::TetScaledJacobian(tet), 1e-13) << "cell " << c;
        }
    }
}
#endif
