// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the quality metrics alone (face_orthogonality.h, face_skewness.h,
// cell_closedness.h, cell_determinant.h, face_weights.h, face_flatness.h, face_tets.h,
// cell_concavity.h, edge_lengths.h, point_nearness.h, cell_regions.h): fields of
// undistorted, sheared and damaged meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "helpers.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/quality/cell_closedness.h"
#include "meshmorph/quality/cell_concavity.h"
#include "meshmorph/quality/cell_determinant.h"
#include "meshmorph/quality/cell_regions.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/edge_lengths.h"
#include "meshmorph/quality/face_flatness.h"
#include "meshmorph/quality/face_orthogonality.h"
#include "meshmorph/quality/face_pyramids.h"
#include "meshmorph/quality/face_skewness.h"
#include "meshmorph/quality/face_tets.h"
#include "meshmorph/quality/face_weights.h"
#include "meshmorph/quality/point_nearness.h"
#include "shape_meshes.h"

using namespace meshmorph;

namespace
{

//! A block sheared in x by `shear` times y: the y-faces are non-orthogonal by atan(shear).
PolyMesh sheared_block(double shear)
{
    return test::make_block_mesh(
        3, 3, 2, [shear](double u, double v, double w) { return Vector3(u + shear * v, v, w); });
}

//! A block of nx x ny x nz hexahedra warped so that its quads are off a plane and skewed,
//! with coordinates that do not round alike.
PolyMesh warped_block(int nx, int ny, int nz)
{
    return test::make_block_mesh(nx, ny, nz,
                                 [](double u, double v, double w)
                                 {
                                     return Vector3(u + 0.1 * std::sin(7 * v + w) + 0.2 * v * v,
                                                    v + 0.03 * std::cos(11 * u * w),
                                                    w + 0.05 * u * v * v);
                                 });
}

//! Face centres and areas of `mesh` as compute_geometry gives them (eight quads at a time
//! where it can) against one face at a time, bit for bit.
void expect_faces_as_one_by_one(const PolyMesh& mesh)
{
    const MeshGeometry g = compute_geometry(mesh);
    Points centres(mesh.n_faces(), 3), areas(mesh.n_faces(), 3);
    for (Index f = 0; f < mesh.n_faces(); ++f)
    {
        face_centre_and_area(mesh, f, centres, areas);
        EXPECT_EQ(g.face_centres.row(f), centres.row(f)) << "face " << f;
        EXPECT_EQ(g.face_areas.row(f), areas.row(f)) << "face " << f;
    }
}

} // namespace

TEST(MeshGeometry, faces_eight_at_a_time_give_the_results_of_one_at_a_time_bit_for_bit)
{
    // Warped quads: few faces (one range of faces, serial), then over 20000 (several
    // ranges, with OpenMP).
    expect_faces_as_one_by_one(warped_block(7, 5, 3));
    PolyMesh warped = warped_block(24, 22, 16);
    ASSERT_GT(warped.n_faces(), 20000);
    expect_faces_as_one_by_one(warped);
    // Degenerate quads: every point in one place (the centre is then the mean, the area 0).
    warped.points.rowwise() = Vector3(0.25, -1.5, 3.0).transpose();
    expect_faces_as_one_by_one(warped);
    // Pentagons and quads mixed in groups of eight.
    expect_faces_as_one_by_one(test::make_pentagon_cells());
    expect_faces_as_one_by_one(test::make_split_top_cube());
}

TEST(FaceSkewness, faces_eight_at_a_time_give_the_results_of_one_at_a_time_bit_for_bit)
{
    for (const PolyMesh& mesh : {warped_block(9, 7, 4), warped_block(24, 22, 16),
                                 test::make_pentagon_cells(), test::make_split_top_cube()})
    {
        const MeshGeometry g = compute_geometry(mesh);
        const Eigen::VectorXd all = face_skewness(mesh, g);
        for (Index f = 0; f < mesh.n_faces(); ++f)
            EXPECT_EQ(all[f], face_skewness_at(mesh, g, f)) << "face " << f;
        EXPECT_GT(all.maxCoeff(), 0.01) << "the premise: skewed faces";
    }
}

//! A block sheared in y beyond x = 0.5 and not before (y rises by 15 per unit of x): the
//! faces at the kink, between an upright and a leaning cell, far above skewness 4.
PolyMesh kinked_block()
{
    return test::make_block_mesh(10, 4, 4,
                                 [](double u, double v, double w)
                                 { return Vector3(u, v + 15.0 * std::max(0.0, u - 0.5), w); });
}

//! screened_face_skewness against face_skewness on `mesh`: the largest value and the faces
//! above `threshold` the same, to the bit.
void expect_screened_as_full(const PolyMesh& mesh, double threshold)
{
    const MeshGeometry g = compute_geometry(mesh);
    const CoupledFaces coupled = coupled_faces(mesh, g, cyclic_patches(mesh, g));
    const Eigen::VectorXd full = face_skewness(mesh, g, coupled);
    const Eigen::VectorXd screened = screened_face_skewness(mesh, g, coupled, threshold);
    EXPECT_EQ(screened.maxCoeff(), full.maxCoeff());
    for (Index f = 0; f < mesh.n_faces(); ++f)
    {
        if (full[f] > threshold)
        {
            EXPECT_EQ(screened[f], full[f]) << "face " << f;
        }
        EXPECT_EQ(screened[f] > threshold, full[f] > threshold) << "face " << f;
        EXPECT_TRUE(screened[f] == full[f] || screened[f] == 0.0) << "face " << f;
    }
    // Fewer computed than all: the screen's premise (its gain) on these meshes.
    EXPECT_LT((screened.array() != 0.0).count(), mesh.n_faces()) << "threshold " << threshold;
}

TEST(FaceSkewness, screened_gives_the_largest_and_the_faces_above_the_threshold_exactly)
{
    const PolyMesh kinked = kinked_block();
    const MeshGeometry g = compute_geometry(kinked);
    ASSERT_GT(face_skewness(kinked, g).maxCoeff(), 4.0) << "the premise: faces above 4";
    expect_screened_as_full(kinked, 4.0); // some faces above: they alone are computed
    expect_screened_as_full(kinked, 1e3); // none above: the largest is searched
    expect_screened_as_full(warped_block(24, 22, 16), 4.0);
    expect_screened_as_full(test::make_pentagon_cells(), 4.0);
    // Cyclic faces measure against the cell across: periodic in x, cells growing along x.
    PolyMesh periodic = test::make_block_mesh(
        6, 3, 3, [](double u, double v, double w) { return Vector3(4 * u * u, v + 0.2 * u, w); });
    periodic.patches[0].type = periodic.patches[1].type = "cyclic";
    periodic.patches[0].entries = {{"neighbourPatch", periodic.patches[1].name}};
    periodic.patches[1].entries = {{"neighbourPatch", periodic.patches[0].name}};
    expect_screened_as_full(periodic, 4.0);
}

TEST(FaceOrthogonality, box_is_orthogonal_and_boundary_faces_are_one)
{
    const PolyMesh mesh = test::make_box_mesh(3, 2, 2);
    const Eigen::VectorXd ortho = face_orthogonality(mesh, compute_geometry(mesh));
    ASSERT_EQ(ortho.size(), mesh.n_faces());
    for (Index f = 0; f < mesh.n_faces(); ++f)
        EXPECT_NEAR(ortho[f], 1.0, 1e-15) << "face " << f;
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
        EXPECT_EQ(ortho[f], 1.0);
}

TEST(FaceOrthogonality, shear_angle_is_the_cell_non_orthogonality)
{
    const PolyMesh mesh = sheared_block(1.0);
    const Eigen::VectorXd ortho = face_orthogonality(mesh, compute_geometry(mesh));
    const Eigen::VectorXd cell = cell_non_orthogonality(cell_faces(mesh), ortho);
    ASSERT_EQ(cell.size(), mesh.n_cells);
    for (Index c = 0; c < mesh.n_cells; ++c)
        EXPECT_NEAR(cell[c], 45.0, 1e-9) << "cell " << c;
    EXPECT_NEAR(non_orthogonality_degrees(std::cos(M_PI / 3)), 60.0, 1e-12);
    EXPECT_EQ(non_orthogonality_degrees(1.5), 0.0); // clamped
}

TEST(FaceSkewness, box_has_no_skewness_and_is_scale_invariant)
{
    for (const double scale : {1e-6, 1.0, 1e6})
    {
        const PolyMesh mesh =
            test::make_box_mesh(2, 3, 2, Vector3::Zero(), Vector3(scale, 2 * scale, scale));
        const Eigen::VectorXd skew = face_skewness(mesh, compute_geometry(mesh));
        EXPECT_LT(skew.maxCoeff(), 1e-9) << "scale " << scale;
        EXPECT_LT(cell_skewness(cell_faces(mesh), skew).maxCoeff(), 1e-9);
    }
}

TEST(CellClosedness, closed_cells_and_aspect_ratio_of_flat_cells)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2, Vector3::Zero(), Vector3(1, 1, 0.1));
    const MeshGeometry g = compute_geometry(mesh);
    const CompactList cf = cell_faces(mesh);
    EXPECT_LT(boundary_openness(mesh, g).cwiseAbs().maxCoeff(), 1e-15);
    const CellClosedness c = cell_closedness(mesh, cf, g, mesh_directions(mesh, g.face_areas));
    EXPECT_LT(c.openness.maxCoeff(), 1e-15);
    for (Index cell = 0; cell < mesh.n_cells; ++cell)
        EXPECT_NEAR(c.aspect_ratio[cell], 10.0, 1e-9); // 0.5 x 0.5 x 0.05 cells
}

TEST(CellDeterminant, cube_cells)
{
    const PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    const MeshGeometry g = compute_geometry(mesh);
    const CompactList cf = cell_faces(mesh);
    const Eigen::VectorXd det =
        cell_determinant(mesh, cf, g, mesh_directions(mesh, g.face_areas), face_area_magnitudes(g));
    EXPECT_NEAR(det[13], 1.0, 1e-12); // the middle cell: 6 internal faces, 2 per axis
    // snappyHexMesh's determinant is 1 for every cube (all faces count).
    const Eigen::VectorXd scaled = cell_area_determinant(cf, g);
    for (Index c = 0; c < mesh.n_cells; ++c)
        EXPECT_NEAR(scaled[c], 1.0, 1e-12);
}

TEST(FaceWeights, halfway_faces_and_volume_ratios)
{
    const PolyMesh mesh = test::make_box_mesh(3, 1, 1);
    const MeshGeometry g = compute_geometry(mesh);
    const Eigen::VectorXd w = face_weights(mesh, g);
    const Eigen::VectorXd ratio = face_volume_ratio(mesh, g.cell_volumes);
    ASSERT_EQ(w.size(), mesh.n_internal_faces());
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
    {
        EXPECT_NEAR(w[f], 0.5, 1e-15);
        EXPECT_NEAR(ratio[f], 1.0, 1e-15);
    }
}

TEST(FaceFlatness, planar_faces_are_flat_and_a_warped_face_is_not)
{
    PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    Eigen::VectorXd mag = face_area_magnitudes(compute_geometry(mesh));
    Eigen::VectorXd flat = face_flatness(mesh, compute_geometry(mesh), mag);
    const Eigen::VectorXd fan = face_fan_areas(mesh, compute_geometry(mesh));
    for (Index f = 0; f < mesh.n_faces(); ++f)
        EXPECT_NEAR(fan[f], mag[f], 1e-15); // a flat face's fan covers it once
    for (Index f = 0; f < mesh.n_faces(); ++f)
        EXPECT_NEAR(flat[f], 1.0, 1e-15);
    mesh.points(7, 2) += 0.5; // lift one corner of the top face
    const MeshGeometry g = compute_geometry(mesh);
    mag = face_area_magnitudes(g);
    flat = face_flatness(mesh, g, mag);
    EXPECT_LT(flat.minCoeff(), 0.99);
}

TEST(FaceTets, valid_box_has_no_errors_and_an_inverted_cell_has)
{
    PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    std::vector<char> errors = face_tet_errors(mesh, compute_geometry(mesh));
    EXPECT_EQ(std::count(errors.begin(), errors.end(), 0), mesh.n_faces());
    mesh.points.row(21) += Eigen::RowVector3d(0.45, 0.4, 0.5);
    errors = face_tet_errors(mesh, compute_geometry(mesh));
    EXPECT_GT(std::count_if(errors.begin(), errors.end(), [](char e) { return e > 0; }), 0);
}

TEST(CellConcavity, box_cells_are_convex)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    const std::vector<char> concave = concave_cells(mesh, cell_faces(mesh), compute_geometry(mesh));
    EXPECT_EQ(std::count(concave.begin(), concave.end(), 0), mesh.n_cells);
}

TEST(FacePyramids, volumes_are_a_sixth_of_the_cell_each_and_wrong_ones_are_counted)
{
    PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    const FacePyramidVolumes v = face_pyramid_volumes(mesh, compute_geometry(mesh));
    for (Index f = 0; f < mesh.n_faces(); ++f)
        EXPECT_NEAR(v.owner[f], 0.125 / 6, 1e-15);
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
        EXPECT_NEAR(v.neighbour[f], 0.125 / 6, 1e-15);
    EXPECT_EQ(count_invalid_cells(mesh, compute_geometry(mesh)).wrong_pyramids, 0);
    mesh.points.row(13) += Eigen::RowVector3d(0.6, 0.6, 0.6); // the middle point, far out
    EXPECT_GT(count_invalid_cells(mesh, compute_geometry(mesh)).wrong_pyramids, 0);
}

TEST(EdgeLengths, extremes_and_the_points_of_short_edges)
{
    PolyMesh mesh = test::make_box_mesh(2, 1, 1, Vector3::Zero(), Vector3(2, 1, 1));
    EdgeLengths e = edge_lengths(mesh, 1e-12);
    EXPECT_DOUBLE_EQ(e.min_length, 1.0);
    EXPECT_DOUBLE_EQ(e.max_length, 1.0);
    EXPECT_EQ(e.n_short, 0);
    mesh.points.row(1) = mesh.points.row(0) + Eigen::RowVector3d(1e-9, 0, 0);
    e = edge_lengths(mesh, 1e-12);
    EXPECT_NEAR(e.min_length, 1e-9, 1e-20);
    // Edge 0-1 is in two faces: the first marks point 0, the second point 1 (OpenFOAM's
    // `set.insert(a) || set.insert(b)`).
    EXPECT_EQ(e.n_short, 2);
    EXPECT_EQ(std::count(e.short_edge_points.begin(), e.short_edge_points.end(), 1), 2);
    EXPECT_TRUE(e.short_edge_points[0] && e.short_edge_points[1]);
}

TEST(CellRegions, numbered_from_the_lowest_cell)
{
    PolyMesh mesh = test::make_box_mesh(3, 1, 1);
    EXPECT_EQ(cell_regions(mesh).size(), 1u);
    // Cut the mesh between cells 0 and 1: face 0 joins them.
    mesh.neighbour[0] = mesh.owner[0];
    const std::vector<std::vector<Index>> regions = cell_regions(mesh);
    ASSERT_EQ(regions.size(), 2u);
    EXPECT_EQ(regions[0], std::vector<Index>{0});
    EXPECT_EQ(regions[1], (std::vector<Index>{1, 2}));
}

TEST(PointNearness, marks_both_points_of_each_close_pair)
{
    PolyMesh mesh = test::make_box_mesh(2, 1, 1, Vector3::Zero(), Vector3(2, 1, 1));
    const std::vector<char> apart = near_points(mesh, 1e-12);
    EXPECT_EQ(std::count(apart.begin(), apart.end(), 1), 0);
    // Point 4, (1 1 0), brought to 1e-7 of point 1, (1 0 0).
    mesh.points.row(4) = mesh.points.row(1) + Eigen::RowVector3d(0, 1e-7, 0);
    const std::vector<char> near = near_points(mesh, 1e-12);
    EXPECT_EQ(std::count(near.begin(), near.end(), 1), 2);
    EXPECT_TRUE(near[1] && near[4]);
    // Not closer than 1e-8.
    const std::vector<char> none = near_points(mesh, 1e-16);
    EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);
}

TEST(PointNearness, compares_only_points_of_similar_magnitude_as_openfoam)
{
    // OpenFOAM compares a point with the points before it in |p|^2 order whose |p|^2 lies
    // within dist^2 below its own. Two points 1e-7 apart along x at x = 1000 differ by
    // 2 * 1000 * 1e-7 = 2e-4 in |p|^2, far more than dist^2 = 1e-12: not compared, so not
    // reported. At the origin the same pair differs by 1e-14 in |p|^2 and is reported.
    PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    mesh.points.row(7) = Eigen::RowVector3d(1000, 0, 0);
    mesh.points.row(6) = Eigen::RowVector3d(1000 + 1e-7, 0, 0);
    std::vector<char> near = near_points(mesh, 1e-12);
    EXPECT_EQ(std::count(near.begin(), near.end(), 1), 0);
    mesh.points.row(7) = Eigen::RowVector3d(0, 0, 1e-7); // point 0 is the origin
    near = near_points(mesh, 1e-12);
    EXPECT_EQ(std::count(near.begin(), near.end(), 1), 2);
    EXPECT_TRUE(near[0] && near[7]);
}

TEST(CellRegions, cyclic_faces_join_regions_as_internal_faces_do)
{
    // Two cells that touch through a pair of coincident boundary faces: two regions, unless
    // the faces form a cyclic pair (regionSplit walks across cyclics).
    PolyMesh mesh = test::make_split_pair_mesh(true);
    EXPECT_EQ(cell_regions(mesh).size(), 2u);
    Patch& split = mesh.patches.back();
    split.n_faces = 1;
    split.name = "left";
    split.type = "cyclic";
    split.entries = {{"neighbourPatch", "right"}};
    split.in_groups.clear();
    Patch right = split;
    right.name = "right";
    right.start_face = split.start_face + 1;
    right.entries = {{"neighbourPatch", "left"}};
    mesh.patches.push_back(right);
    const std::vector<std::vector<Index>> regions = cell_regions(mesh);
    ASSERT_EQ(regions.size(), 1u);
    EXPECT_EQ(regions[0], (std::vector<Index>{0, 1}));
    EXPECT_EQ(region_of_cells(regions, 2), (std::vector<Index>{0, 0}));
}
