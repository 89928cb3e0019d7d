// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of meshmorph/quality/check_mesh.h and mesh_geometry.h on generated meshes: the
// reference case of docs/checkmesh-spec.md §7 (OpenFOAM v1912's printed values) and
// properties of undistorted and damaged meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/check_mesh.h"
#include "meshmorph/quality/report_text.h"

using namespace meshmorph;

namespace
{

//! The spec §7 mesh: blockMesh's 2x2x2 unit cube, point 13 moved to (0.6, 0.5, 0.5).
PolyMesh reference_cube(bool moved = true)
{
    PolyMesh mesh;
    mesh.points.resize(27, 3);
    for (int l = 0; l < 3; ++l)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
                mesh.points.row(i + 3 * j + 9 * l) = Eigen::RowVector3d(0.5 * i, 0.5 * j, 0.5 * l);
    if (moved)
        mesh.points.row(13) = Eigen::RowVector3d(0.6, 0.5, 0.5);
    const std::vector<std::array<Index, 4>> faces = {
        {1, 4, 13, 10},   {3, 12, 13, 4},   {9, 10, 13, 12},  {4, 13, 14, 5},   {10, 11, 14, 13},
        {4, 7, 16, 13},   {12, 13, 16, 15}, {13, 14, 17, 16}, {10, 13, 22, 19}, {12, 21, 22, 13},
        {13, 22, 23, 14}, {13, 16, 25, 22}, {0, 9, 12, 3},    {3, 12, 15, 6},   {9, 18, 21, 12},
        {12, 21, 24, 15}, {2, 5, 14, 11},   {5, 8, 17, 14},   {11, 14, 23, 20}, {14, 17, 26, 23},
        {0, 1, 10, 9},    {9, 10, 19, 18},  {1, 2, 11, 10},   {10, 11, 20, 19}, {6, 15, 16, 7},
        {15, 24, 25, 16}, {7, 16, 17, 8},   {16, 25, 26, 17}, {0, 3, 4, 1},     {3, 6, 7, 4},
        {1, 4, 5, 2},     {4, 7, 8, 5},     {18, 19, 22, 21}, {21, 22, 25, 24}, {19, 20, 23, 22},
        {22, 23, 26, 25}};
    for (const auto& f : faces)
        mesh.faces.push_back(std::span<const Index>(f));
    mesh.owner = {0, 0, 0, 1, 1, 2, 2, 3, 4, 4, 5, 6, 0, 2, 4, 6, 1, 3,
                  5, 7, 0, 4, 1, 5, 2, 6, 3, 7, 0, 2, 1, 3, 4, 6, 5, 7};
    mesh.neighbour = {1, 2, 4, 3, 5, 3, 6, 7, 5, 6, 7, 7};
    mesh.patches = {{"walls", "wall", 12, 16, {}, {}},
                    {"bottom", "patch", 28, 4, {}, {}},
                    {"top", "patch", 32, 4, {}, {}}};
    mesh.finalize();
    return mesh;
}

//! Lines of `text` containing `needle`.
std::string line_with(const std::string& text, const std::string& needle)
{
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        if (line.find(needle) != std::string::npos)
            return line;
    return "<no line with '" + needle + "'>";
}

} // namespace

TEST(MeshGeometry, reference_case_face_and_cell_values)
{
    const PolyMesh mesh = reference_cube();
    const MeshGeometry g = compute_geometry(mesh);
    // Spec §7 intermediate values (15 digits, from OpenFOAM v1912).
    EXPECT_NEAR(g.face_centres(0, 0), 0.525161827552972, 1e-15);
    EXPECT_NEAR(g.face_centres(0, 1), 0.250809137764858, 1e-15);
    EXPECT_NEAR(g.face_centres(0, 2), 0.250809137764858, 1e-15);
    EXPECT_DOUBLE_EQ(g.face_areas(0, 0), 0.25);
    EXPECT_DOUBLE_EQ(g.face_areas(0, 1), -0.025);
    EXPECT_DOUBLE_EQ(g.face_areas(0, 2), -0.025);
    EXPECT_NEAR(g.cell_centres(0, 0), 0.263015151077013, 1e-15);
    EXPECT_NEAR(g.cell_centres(0, 1), 0.25406385062316, 1e-15);
    EXPECT_NEAR(g.cell_volumes[0], 0.13125, 1e-16);
    EXPECT_NEAR(g.cell_volumes[1], 0.11875, 1e-16);
    EXPECT_DOUBLE_EQ(g.face_centres(12, 0), 0.0);
    EXPECT_DOUBLE_EQ(g.face_centres(12, 1), 0.25);
}

TEST(CheckMesh, reference_case_prints_openfoam_values)
{
    const PolyMesh mesh = reference_cube();
    CheckMeshSettings settings;
    settings.all_geometry = true;
    const QualityReport r = check_mesh(mesh, settings);
    // The expected lines of spec §7 (checkMesh -allGeometry, writePrecision 6).
    const std::vector<std::string> expected = {
        "    Boundary openness (0 0 0) OK.",
        "    Max cell openness = 1.00929e-16 OK.",
        "    Max aspect ratio = 1.1 OK.",
        "    Minimum face area = 0.225. Maximum face area = 0.275.  Face area magnitudes OK.",
        "    Min volume = 0.11875. Max volume = 0.13125.  Total volume = 1.  Cell volumes OK.",
        "    Mesh non-orthogonality Max: 6.69292 average: 3.8627",
        "    Non-orthogonality check OK.",
        "    Face pyramids OK.",
        "    Max skewness = 0.04355 OK.",
        "    Coupled point location match (average 0) OK.",
        "    Face tets OK.",
        "    Min/max edge length = 0.4 0.6 OK.",
        "    All angles in faces OK.",
        "    Face flatness (1 = flat, 0 = butterfly) : min = 0.995181  average = 0.999465",
        "    All face flatness OK.",
        "    Cell determinant (wellposedness) : minimum: 0.121455 average: 0.121708",
        "    Cell determinant check OK.",
        "    Concave cell check OK.",
        "    Face interpolation weight : minimum: 0.475063 average: 0.491688",
        "    Face interpolation weight check OK.",
        "    Face volume ratio : minimum: 0.904762 average: 0.968254",
        "    Face volume ratio check OK."};
    std::string block;
    for (const std::string& line : expected)
        block += line + "\n";
    EXPECT_NE(r.text.find(block), std::string::npos) << r.text;
    EXPECT_NE(r.text.find("\nMesh OK.\n"), std::string::npos);
    EXPECT_TRUE(r.mesh_ok());
    EXPECT_EQ(r.cell_types.hex, 8);
}

TEST(CheckMesh, reference_case_at_15_digits)
{
    CheckMeshSettings settings;
    settings.write_precision = 15;
    const QualityReport r = check_mesh(reference_cube(), settings);
    EXPECT_EQ(line_with(r.text, "non-orthogonality Max"),
              "    Mesh non-orthogonality Max: 6.69292497322759 average: 3.86269686643295");
    EXPECT_EQ(line_with(r.text, "Max skewness"), "    Max skewness = 0.0435500178548794 OK.");
    EXPECT_EQ(line_with(r.text, "Max cell openness"),
              "    Max cell openness = 1.00929365875014e-16 OK.");
}

TEST(CheckMesh, unmoved_cube_is_perfect)
{
    CheckMeshSettings settings;
    settings.all_geometry = true;
    const QualityReport r = check_mesh(reference_cube(false), settings);
    EXPECT_EQ(r.max_non_orthogonality, 0.0);
    EXPECT_EQ(r.max_skewness, 0.0);
    EXPECT_DOUBLE_EQ(r.max_aspect_ratio, 1.0);
    for (Index c = 0; c < r.n_cells; ++c)
        EXPECT_DOUBLE_EQ(r.cell_determinant[c], 0.125);
    EXPECT_TRUE(r.mesh_ok());
}

TEST(CheckMesh, empty_cell_zone_prints_openfoams_inverted_box)
{
    // checkMesh on a split-region case: an empty cellZone's bounding box is boundBox's
    // invertedBox, +-ROOTVGREAT (1e+150), not +-VGREAT.
    PolyMesh mesh = reference_cube(false);
    mesh.cell_zones.push_back(Zone{"empty", "cellZone", {}, {}, {}});
    mesh.cell_zones.push_back(Zone{"all", "cellZone", {0}, {}, {}});
    const CheckMeshSettings settings;
    const QualityReport r = check_mesh(mesh, settings);
    ASSERT_EQ(r.cell_zones.size(), 2u);
    EXPECT_EQ(r.cell_zones[0].n_points, 0);
    EXPECT_EQ(r.cell_zones[0].bb_min, Vector3::Constant(1e150));
    EXPECT_EQ(r.cell_zones[0].bb_max, Vector3::Constant(-1e150));
    EXPECT_EQ(r.cell_zones[1].bb_min, mesh.points.colwise().minCoeff().transpose());
    const std::string text = report_text(r, settings);
    EXPECT_NE(text.find("(1e+150 1e+150 1e+150) (-1e+150 -1e+150 -1e+150)"), std::string::npos)
        << text;
}

TEST(CheckMesh, scaled_domains_keep_relative_metrics)
{
    // Non-dimensional metrics do not depend on the length scale (1e-6 .. 1e6).
    for (double scale : {1e-6, 1.0, 1e6})
    {
        PolyMesh mesh = test::make_block_mesh(
            3, 2, 2,
            [&](double u, double v, double w)
            { return Vector3(scale * (u + 0.1 * v * v), scale * v, scale * (w + 0.05 * u)); });
        CheckMeshSettings settings;
        settings.all_geometry = true;
        const QualityReport r = check_mesh(mesh, settings);
        PolyMesh unit = test::make_block_mesh(3, 2, 2,
                                              [&](double u, double v, double w) {
                                                  return Vector3(u + 0.1 * v * v, v, w + 0.05 * u);
                                              });
        const QualityReport ru = check_mesh(unit, settings);
        EXPECT_NEAR(r.max_non_orthogonality, ru.max_non_orthogonality, 1e-9);
        EXPECT_NEAR(r.max_skewness, ru.max_skewness, 1e-9);
        EXPECT_NEAR(r.min_determinant, ru.min_determinant, 1e-9);
        EXPECT_NEAR(r.total_volume / std::pow(scale, 3), ru.total_volume, 1e-12);
    }
}

TEST(CheckMesh, inverted_cell_fails_volume_pyramid_and_tet_checks)
{
    PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    // Push an interior point far through the opposite corner: cells around it invert.
    const Index p = 1 + 4 * (1 + 4 * 1);
    mesh.points.row(p) = Eigen::RowVector3d(0.9, 0.9, 0.9);
    CheckMeshSettings settings;
    settings.all_geometry = true;
    settings.report_sets = true;
    const QualityReport r = check_mesh(mesh, settings);
    EXPECT_FALSE(r.mesh_ok());
    EXPECT_GT(r.negative_volume_cells, 0);
    EXPECT_GT(r.incorrectly_oriented_face_pyramids, 0);
    EXPECT_GT(r.face_tet_errors, 0);
    EXPECT_NE(r.text.find(" ***Zero or negative cell volume detected."), std::string::npos);
    EXPECT_NE(r.text.find("Failed " + std::to_string(r.failed_checks) + " mesh checks."),
              std::string::npos);
    bool has_zero_volume_set = false;
    for (const MeshSet& s : r.sets)
        if (s.name == "zeroVolumeCells")
        {
            has_zero_volume_set = true;
            EXPECT_EQ(static_cast<Index>(s.labels.size()), r.negative_volume_cells);
        }
    EXPECT_TRUE(has_zero_volume_set);
}

namespace
{
//! A 6 x 5 x 4 block bent in every direction: no metric is trivial on it.
PolyMesh distorted_block()
{
    return test::make_block_mesh(6, 5, 4,
                                 [](double u, double v, double w) {
                                     return Vector3(u + 0.2 * std::sin(3 * v) * w, v + 0.1 * u * u,
                                                    w + 0.1 * std::cos(4 * u));
                                 });
}
} // namespace

TEST(CheckMesh, results_do_not_depend_on_thread_count)
{
    PolyMesh mesh = distorted_block();
    CheckMeshSettings settings;
    settings.all_geometry = true;
    settings.all_topology = true;
    settings.write_precision = 17;
    const QualityReport many = check_mesh(mesh, settings);
#ifdef _OPENMP
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const QualityReport one = check_mesh(mesh, settings);
    omp_set_num_threads(threads);
    EXPECT_EQ(one.text, many.text);
#endif
    EXPECT_FALSE(many.text.empty());
}

namespace
{
//! The mesh with its internal points numbered first, as blockMesh numbers them (checkMesh
//! counts edges for -allTopology only then).
PolyMesh internal_points_first(PolyMesh mesh)
{
    const std::vector<char> boundary = boundary_point_mask(mesh);
    std::vector<Index> new_label(boundary.size());
    Index next = 0;
    for (const char on_boundary : {0, 1})
        for (std::size_t p = 0; p < boundary.size(); ++p)
            if (boundary[p] == on_boundary)
                new_label[p] = next++;
    Points points(mesh.points.rows(), 3);
    for (Index p = 0; p < mesh.n_points(); ++p)
        points.row(new_label[std::size_t(p)]) = mesh.points.row(p);
    mesh.points = points;
    for (Index& label : mesh.faces.values)
        label = new_label[std::size_t(label)];
    return mesh;
}
} // namespace

TEST(CheckMesh, a_mesh_large_enough_for_threads_gives_the_same_report_on_any_thread_count)
{
    // 32^3 cells, 101376 faces: above the size where the geometry and check loops run on
    // OpenMP's threads in pieces taken as threads come free (20000 faces, pieces of
    // detail::loop_piece) and where the largest skewness is reduced on threads (65536), so
    // that the pieces are really spread. Points pushed through their neighbours all over the
    // block fail several checks in several pieces.
    PolyMesh mesh = internal_points_first(test::make_block_mesh(
        32, 32, 32,
        [](double u, double v, double w)
        { return Vector3(u + 0.15 * std::sin(3 * v) * w, v + 0.1 * u * u, w); }));
    for (Index p = 1000; p < mesh.n_points(); p += 3001)
        mesh.points.row(p) += Eigen::RowVector3d(0.05, 0.04, 0.045);
    CheckMeshSettings settings;
    settings.all_geometry = true;
    settings.all_topology = true;
    settings.write_precision = 17;
    const QualityReport many = check_mesh(mesh, settings);
    ASSERT_GT(mesh.n_faces(), 65536);
    ASSERT_GE(many.failed_checks, 2) << many.text;
    ASSERT_GE(many.sets.size(), 2u);
    ASSERT_TRUE(many.edges.has_value()) << "-allTopology counts edges";
#ifdef _OPENMP
    const int threads = omp_get_max_threads();
    for (const int n : {1, 3})
    {
        omp_set_num_threads(n);
        const QualityReport other = check_mesh(mesh, settings);
        EXPECT_EQ(other.text, many.text) << n << " threads";
        ASSERT_EQ(other.sets.size(), many.sets.size()) << n << " threads";
        for (std::size_t s = 0; s < many.sets.size(); ++s)
            EXPECT_EQ(other.sets[s].labels, many.sets[s].labels) << many.sets[s].name;
    }
    omp_set_num_threads(threads);
#endif
}

TEST(CheckMesh, without_cell_fields_the_summary_is_the_same)
{
    // A distorted block with an inverted cell: every summary line has something to say.
    PolyMesh mesh = distorted_block();
    mesh.points.row(40) += Eigen::RowVector3d(0.4, 0.3, 0.3);
    for (const bool all_geometry : {false, true})
    {
        CheckMeshSettings settings;
        settings.all_geometry = all_geometry;
        settings.write_precision = 17;
        const QualityReport with = check_mesh(mesh, settings);
        settings.cell_fields = false;
        const QualityReport without = check_mesh(mesh, settings);
        EXPECT_EQ(without.text, with.text) << "allGeometry " << all_geometry;
        EXPECT_EQ(without.failed_checks, with.failed_checks);
        EXPECT_EQ(without.min_scaled_jacobian, with.min_scaled_jacobian);
        EXPECT_EQ(with.cell_non_orthogonality.size(), mesh.n_cells);
        EXPECT_EQ(with.cell_determinant.size(), mesh.n_cells);
        EXPECT_EQ(without.cell_non_orthogonality.size(), 0);
        EXPECT_EQ(without.cell_skewness.size(), 0);
        // -allGeometry checks the determinant, so it is computed either way.
        EXPECT_EQ(without.cell_determinant.size(), all_geometry ? mesh.n_cells : 0);
    }
}

TEST(CheckMesh, a_check_after_the_points_moved_takes_over_what_did_not_change)
{
    // A morph's check after: the topology and mesh statistics from the check before, the
    // face pyramid errors its last step counted. The report is a fresh check's.
    const PolyMesh original = distorted_block();
    const CompactList cf = cell_faces(original);
    CheckMeshSettings settings;
    settings.write_precision = 17;
    const QualityReport before = check_mesh(original, cf, compute_geometry(original, cf), settings);
    PolyMesh moved = original;
    // An interior point pushed about two cells through its neighbours: the cells around it
    // invert (9 wrongly oriented pyramids, 1 negative volume), far from any threshold.
    moved.points.row(101) += Eigen::RowVector3d(0.6, 0.45, 0.45);
    const MeshGeometry g = compute_geometry(moved, cf);
    std::vector<char> pyramid_errors;
    const InvalidCells invalid = count_invalid_cells(moved, g, &pyramid_errors);
    ASSERT_GT(invalid.wrong_pyramids, 0);
    ASSERT_GT(invalid.negative_volume_cells, 0);
    ASSERT_EQ(Index(pyramid_errors.size()), moved.n_faces());
    const QualityReport fresh = check_mesh(moved, cf, g, settings);
    CheckMeshSettings after_settings = settings;
    after_settings.unchanged_topology = &before;
    after_settings.face_pyramid_errors = &pyramid_errors;
    const QualityReport after = check_mesh(moved, cf, g, after_settings);
    EXPECT_EQ(after.text, fresh.text);
    EXPECT_EQ(after.incorrectly_oriented_face_pyramids, invalid.wrong_pyramids);
    EXPECT_EQ(after.negative_volume_cells, invalid.negative_volume_cells);
    EXPECT_EQ(after.cell_types.hex, fresh.cell_types.hex);
    EXPECT_EQ(after.n_internal_points, fresh.n_internal_points);
    // Errors of another size (not of these faces) are not taken: computed afresh.
    const std::vector<char> wrong(std::size_t(moved.n_faces() - 1), 2);
    after_settings.face_pyramid_errors = &wrong;
    EXPECT_EQ(check_mesh(moved, cf, g, after_settings).text, fresh.text);
}

TEST(CheckMesh, rejects_out_of_range_vertex_labels)
{
    PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    mesh.faces.values[0] = 99;
    EXPECT_THROW(check_mesh(mesh, CheckMeshSettings{}), InvalidInput);
}

TEST(CheckMesh, a_point_that_is_not_finite_makes_the_mesh_invalid)
{
    // An overflowing morph once wrote inf/NaN points that the check called "Mesh OK" (every
    // comparison with NaN is false); checkMesh itself stops there with a floating-point
    // exception. Such cells count as negative volumes and their faces as wrongly oriented.
    for (const double bad :
         {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(), 1e300})
    {
        PolyMesh mesh = test::make_box_mesh(3, 3, 3);
        mesh.points(21, 1) = bad; // an interior point of the 3^3 box
        mesh.points(21, 0) = bad == 1e300 ? -1e300 : bad;
        const CompactList cf = cell_faces(mesh);
        const MeshGeometry g = compute_geometry(mesh, cf);
        const InvalidCells invalid = count_invalid_cells(mesh, g);
        EXPECT_GT(invalid.negative_volume_cells + invalid.wrong_pyramids, 0) << bad;
        const QualityReport r = check_mesh(mesh, cf, g, CheckMeshSettings{});
        EXPECT_FALSE(r.mesh_ok()) << bad;
        EXPECT_GT(r.negative_volume_cells + r.incorrectly_oriented_face_pyramids, 0) << bad;
    }
}
