// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the check tier (check_result.h, geometry_checks.h, topology_checks.h,
// mesh_quality_checks.h) and of the report walkers (report_text.h, quality_json.h).
#include <gtest/gtest.h>

#include <array>
#include <stdexcept>

#include "helpers.h"
#include "meshmorph/mesh/point_faces.h"
#include "meshmorph/quality/cell_regions.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/check_mesh.h"
#include "meshmorph/quality/face_orthogonality.h"
#include "meshmorph/quality/face_skewness.h"
#include "meshmorph/quality/geometry_checks.h"
#include "meshmorph/quality/mesh_quality_checks.h"
#include "meshmorph/quality/quality_json.h"
#include "meshmorph/quality/report_text.h"
#include "meshmorph/quality/topology_checks.h"
#include "meshmorph/quality/zone_topology.h"

using namespace meshmorph;

TEST(CheckResult, sets_are_sorted_distinct_and_empty_ones_dropped)
{
    CheckResult r(CheckId::face_areas);
    r.add_set("empty", MeshSet::Kind::face, {}, "nothing");
    r.add_set("some", MeshSet::Kind::cell, {5, 1, 5, 3}, "cells");
    ASSERT_EQ(r.sets.size(), 1u);
    EXPECT_EQ(r.sets[0].set.labels, (std::vector<Index>{1, 3, 5}));
    EXPECT_FALSE(r.failed());
    r.add("n", Index{3});
    r.add("x", 0.5);
    EXPECT_EQ(r.count("n"), 3);
    EXPECT_EQ(r.real("x"), 0.5);
    EXPECT_EQ(r.find("y"), nullptr);
    EXPECT_THROW(r.real("n"), std::logic_error); // a count is not a real
}

TEST(GeometryChecks, cell_volumes_threshold_statistics_and_set)
{
    const CheckResult r = check_cell_volumes(Eigen::Vector3d(1.0, -1.0, 0.5));
    EXPECT_EQ(r.failure, "cellVolumes");
    EXPECT_EQ(r.count("negativeVolumeCells"), 1);
    EXPECT_EQ(r.real("minVolume"), -1.0);
    EXPECT_EQ(r.real("maxVolume"), 1.0);
    EXPECT_EQ(r.real("totalVolume"), 0.5);
    ASSERT_EQ(r.sets.size(), 1u);
    EXPECT_EQ(r.sets[0].set.name, "zeroVolumeCells");
    EXPECT_EQ(r.sets[0].set.labels, std::vector<Index>{1});
    EXPECT_FALSE(check_cell_volumes(Eigen::Vector3d(1.0, 2.0, 0.5)).failed());
}

TEST(GeometryChecks, face_weight_minimum_average_and_failure)
{
    const CheckResult r = check_face_weight(Eigen::Vector2d(0.5, 0.01));
    EXPECT_EQ(r.failure, "faceWeight");
    EXPECT_EQ(r.real("minFaceWeight"), 0.01);
    EXPECT_EQ(r.real("avgFaceWeight"), 0.255);
    EXPECT_EQ(r.count("lowWeightFaces"), 1);
    // No internal faces: checkMesh's zeros.
    const CheckResult none = check_face_weight(Eigen::VectorXd());
    EXPECT_EQ(none.real("minFaceWeight"), 0.0);
    EXPECT_FALSE(none.failed());
}

TEST(GeometryChecks, severe_non_orthogonality_warns_and_errors_fail)
{
    const PolyMesh mesh = test::make_block_mesh(
        3, 3, 2, [](double u, double v, double w) { return Vector3(u + 3.2 * v, v, w); });
    const MeshGeometry g = compute_geometry(mesh);
    const CoupledFaces internal = coupled_faces(mesh, g, {});
    const CheckResult r =
        check_face_orthogonality(face_orthogonality(mesh, g), internal.statistics_faces());
    EXPECT_NEAR(r.real("maxNonOrthogonality"), std::atan(3.2) * 180 / M_PI, 1e-9);
    EXPECT_EQ(r.count("severelyNonOrthogonalFaces"), 24); // internal x- and y-faces, 12 each
    EXPECT_FALSE(r.failed());
    const CheckResult errors = check_face_orthogonality(Eigen::Vector2d(-0.5, 1.0), {1, 0});
    EXPECT_EQ(errors.failure, "nonOrthogonality");
    EXPECT_EQ(errors.count("nonOrthogonalityErrors"), 1);
}

TEST(TopologyChecks, unused_points_fail)
{
    PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    EXPECT_FALSE(check_point_usage(mesh).failed());
    mesh.points.conservativeResize(9, 3);
    mesh.points.row(8) = Eigen::RowVector3d(2, 2, 2);
    const CheckResult r = check_point_usage(mesh);
    EXPECT_EQ(r.failure, "unusedPoints");
    ASSERT_EQ(r.sets.size(), 1u);
    EXPECT_EQ(r.sets[0].set.labels, std::vector<Index>{8});
}

TEST(MeshQualityChecks, each_criterion_counts_the_faces_it_adds)
{
    const PolyMesh mesh = test::make_block_mesh(
        3, 3, 2, [](double u, double v, double w) { return Vector3(u + v, v, w); });
    const MeshGeometry g = compute_geometry(mesh);
    MeshQualitySettings q;
    q.max_non_ortho = 30; // flags the 24 internal x- and y-faces (45 degrees)
    q.min_area = 1e9;     // flags every face, but only the others are new
    const CoupledFaces coupled = coupled_faces(mesh, g, {});
    const CheckResult r =
        check_mesh_quality(mesh, cell_faces(mesh), g, q, face_skewness(mesh, g), coupled);
    const Statistic::Counts& counts = r.counts("meshQualityFailures");
    ASSERT_EQ(counts.size(), 2u);
    EXPECT_EQ(counts[0], (std::pair<std::string, Index>{"maxNonOrtho", 24}));
    EXPECT_EQ(counts[1].first, "minArea");
    EXPECT_EQ(counts[1].second, mesh.n_faces() - 24);
    EXPECT_EQ(r.count("meshQualityFaces"), mesh.n_faces());
    EXPECT_EQ(r.failure, "meshQuality");
}

TEST(QualityReport, failures_sets_and_headline_numbers_come_from_the_checks)
{
    PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    mesh.points.row(21) += Eigen::RowVector3d(0.45, 0.4, 0.5); // inverts cells
    CheckMeshSettings settings;
    settings.all_geometry = true;
    const QualityReport r = check_mesh(mesh, settings);
    Index failed = 0;
    for (const CheckResult& c : r.checks)
        failed += c.failed();
    EXPECT_EQ(r.failed_checks, failed);
    EXPECT_EQ(r.failed_check_names.size(), static_cast<std::size_t>(failed));
    EXPECT_EQ(r.negative_volume_cells, std::get<Index>(r.statistic("negativeVolumeCells")->value));
    EXPECT_EQ(r.max_skewness, std::get<double>(r.statistic("maxSkewness")->value));
    EXPECT_GT(r.negative_volume_cells, 0);
    const InvalidCells invalid = count_invalid_cells(mesh, compute_geometry(mesh));
    EXPECT_EQ(invalid.negative_volume_cells, r.negative_volume_cells);
    EXPECT_EQ(invalid.wrong_pyramids, r.incorrectly_oriented_face_pyramids);
    EXPECT_EQ(report_text(r, settings), r.text);
}

TEST(QualityReport, a_new_check_reaches_the_json_without_touching_the_json_writer)
{
    QualityReport r = check_mesh(test::make_box_mesh(1, 1, 1), CheckMeshSettings{});
    // A check the report has no lines for yet (one past the last id).
    CheckResult extra(static_cast<CheckId>(static_cast<int>(CheckId::mesh_quality) + 1));
    extra.add("extraMetric", 0.25);
    extra.add("extraTextOnly", Index{2}, false);
    r.checks.push_back(extra);
    const nlohmann::json j = quality_json(r);
    EXPECT_EQ(j.at("extraMetric"), 0.25);
    EXPECT_FALSE(j.contains("extraTextOnly"));
    // The text report needs a formatter for it.
    EXPECT_THROW(report_text(r, CheckMeshSettings{}), std::logic_error);
}

TEST(TopologyChecks, regions_touching_at_points_are_point_connected)
{
    // The baffle pair: two cells whose boundary faces share 4 points.
    const PolyMesh mesh = test::make_split_pair_mesh(true);
    const std::vector<std::vector<Index>> regions = cell_regions(mesh);
    ASSERT_EQ(regions.size(), 2u);
    const CheckResult plain = check_regions(mesh, regions, false);
    EXPECT_EQ(plain.count("regions"), 2);
    EXPECT_EQ(plain.find("regionDisconnected"), nullptr);
    ASSERT_EQ(plain.sets.size(), 2u); // region0, region1
    const CheckResult r = check_regions(mesh, regions, true);
    EXPECT_EQ(r.counts("regionDisconnected"), (Statistic::Counts{{"region0", 0}, {"region1", 0}}));
    ASSERT_EQ(r.sets.size(), 3u);
    EXPECT_EQ(r.sets[2].set.name, "multiRegionPoints");
    // The 4 points of the x = 1 plane: pid(1, j, k) = 1 + 3 (j + 2 k).
    EXPECT_EQ(r.sets[2].set.labels, (std::vector<Index>{1, 4, 7, 10}));
    EXPECT_FALSE(r.failed());
}

TEST(TopologyChecks, baffle_faces_go_into_the_edge_faces_set)
{
    // The baffle pair's two split faces (10 and 11, after the 10 faces of the box's six
    // patches) have the same 4 points: one baffle, both faces in edgeFaces, no failure.
    const PolyMesh mesh = test::make_split_pair_mesh(true);
    const CheckResult r = check_face_faces(face_face_connectivity(mesh, point_faces(mesh)));
    EXPECT_EQ(r.count("baffleFaces"), 1);
    EXPECT_EQ(r.count("duplicateFaces"), 0);
    ASSERT_EQ(r.sets.size(), 1u);
    EXPECT_EQ(r.sets[0].set.name, "edgeFaces");
    EXPECT_EQ(r.sets[0].set.labels, (std::vector<Index>{10, 11}));
    EXPECT_FALSE(r.failed());
    // Without the baffle, no pair and no set.
    const PolyMesh box = test::make_box_mesh(2, 1, 1);
    EXPECT_TRUE(check_face_faces(face_face_connectivity(box, point_faces(box))).sets.empty());
}

TEST(TopologyChecks, regions_without_shared_points_are_fully_disconnected)
{
    const PolyMesh mesh = test::make_split_pair_mesh(false);
    const CheckResult r = check_regions(mesh, cell_regions(mesh), true);
    EXPECT_EQ(r.counts("regionDisconnected"), (Statistic::Counts{{"region0", 1}, {"region1", 1}}));
    ASSERT_EQ(r.sets.size(), 2u); // no multiRegionPoints
    EXPECT_EQ(r.sets[0].set.labels, std::vector<Index>{0});
    EXPECT_EQ(r.sets[1].set.labels, std::vector<Index>{1});
}

TEST(GeometryChecks, near_points_set_only_when_it_adds_to_the_short_edges)
{
    EdgeLengths lengths;
    lengths.short_edge_points = {1, 0, 0, 0};
    lengths.n_short = 1;
    // The near pair (0, 1) adds point 1: the set is the union.
    CheckResult r = check_edge_length(lengths, {1, 1, 0, 0}, 1e-12);
    ASSERT_EQ(r.sets.size(), 2u);
    EXPECT_EQ(r.sets[1].set.name, "nearPoints");
    EXPECT_EQ(r.sets[1].set.labels, (std::vector<Index>{0, 1}));
    EXPECT_DOUBLE_EQ(r.real("nearPointDistance"), 1e-6);
    // Near points already on short edges: no nearPoints set.
    r = check_edge_length(lengths, {1, 0, 0, 0}, 1e-12);
    ASSERT_EQ(r.sets.size(), 1u);
    EXPECT_EQ(r.sets[0].set.name, "shortEdges");
}

TEST(ReportText, region_and_near_point_lines_as_checkmesh_prints_them)
{
    // The fully disconnected pair: cell 1's points at x = 1 are copies 0 apart from cell 0's.
    CheckMeshSettings settings;
    settings.all_geometry = settings.all_topology = settings.report_sets = true;
    settings.time_name = "0";
    QualityReport r = check_mesh(test::make_split_pair_mesh(false), settings);
    EXPECT_NE(r.text.find("   *Number of regions: 2\n"
                          "    The mesh has multiple regions which are not connected by any "
                          "face.\n"
                          "  <<Writing region information to \"0/cellToRegion\"\n"
                          "  <<Writing region 0 (fully disconnected) with 1 cells to cellSet "
                          "region0\n"
                          "  <<Writing region 1 (fully disconnected) with 1 cells to cellSet "
                          "region1\n"),
              std::string::npos)
        << r.text;
    // sqrt(|1e-6 * (2 1 1)|^2) = 1e-6 sqrt(6); 8 points: the 4 pairs.
    EXPECT_NE(r.text.find("  <<Writing 8 near (closer than 2.44949e-06 apart) points to set "
                          "nearPoints\n"),
              std::string::npos)
        << r.text;
    EXPECT_EQ(r.cell_to_region, (std::vector<Index>{0, 1}));
    // The baffle pair, -allTopology: point connected, the shared points as a set.
    r = check_mesh(test::make_split_pair_mesh(true), settings);
    EXPECT_NE(r.text.find("  <<Writing region 1 (point connected) with 1 cells to cellSet "
                          "region1\n"
                          "  <<Writing 4 points that are in multiple regions to set "
                          "multiRegionPoints\n"),
              std::string::npos)
        << r.text;
    // Without -allTopology no connection word; without -writeSets no "<<Writing" line.
    settings.all_topology = false;
    r = check_mesh(test::make_split_pair_mesh(true), settings);
    EXPECT_NE(r.text.find("  <<Writing region 0 with 1 cells to cellSet region0\n"),
              std::string::npos)
        << r.text;
    settings.report_sets = false;
    r = check_mesh(test::make_split_pair_mesh(true), settings);
    EXPECT_EQ(r.text.find("<<Writing"), std::string::npos) << r.text;
    EXPECT_NE(r.text.find("   *Number of regions: 2\n"), std::string::npos);
}

TEST(SurfaceTopology, non_manifold_points_are_those_of_shared_edges_and_pinched_fans)
{
    // Three quads on the edge 0-1 (a book of three pages): the edge's points are checkMesh's
    // nonManifoldPoints. Two closed tetrahedra surfaces touching at point 0: a pinched fan.
    PolyMesh book;
    book.points.resize(8, 3);
    book.points << 0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, -1, 0, 0, -1, 0, 1;
    book.faces.push_back({0, 1, 3, 2});
    book.faces.push_back({0, 4, 5, 1});
    book.faces.push_back({0, 1, 7, 6});
    const SurfaceTopology pages = surface_topology(book, "book", {0, 1, 2});
    EXPECT_EQ(pages.type, "multiply connected (shared edge)");
    EXPECT_EQ(pages.edge_points, (std::vector<Index>{0, 1}));
    EXPECT_TRUE(pages.fan_points.empty());

    PolyMesh pinch;
    pinch.points.resize(7, 3);
    pinch.points << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1;
    for (const auto& f : std::vector<std::array<Index, 3>>{{0, 2, 1},
                                                           {0, 1, 3},
                                                           {0, 3, 2},
                                                           {1, 2, 3},
                                                           {0, 5, 4},
                                                           {0, 4, 6},
                                                           {0, 6, 5},
                                                           {4, 5, 6}})
        pinch.faces.push_back({f[0], f[1], f[2]});
    const SurfaceTopology touching = surface_topology(pinch, "pinch", {0, 1, 2, 3, 4, 5, 6, 7});
    EXPECT_EQ(touching.type, "multiply connected (shared point)");
    EXPECT_TRUE(touching.edge_points.empty());
    EXPECT_EQ(touching.fan_points, (std::vector<Index>{0}));
}
