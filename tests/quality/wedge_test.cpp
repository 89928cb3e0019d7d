// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the wedge (axisymmetric) support: wedge_geometry.h (OpenFOAM's wedgePolyPatch
// centreNormal, angle and axis), the mesh directions it implies (mesh_geometry.h) and the
// wedge check (wedge_alignment.h, check_wedges, its report lines) on synthetic wedges.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.h"
#include "meshmorph/mesh/wedge_geometry.h"
#include "meshmorph/quality/check_mesh.h"
#include "meshmorph/quality/geometry_checks.h"
#include "meshmorph/quality/quality_json.h"
#include "meshmorph/quality/wedge_alignment.h"

using namespace meshmorph;

namespace
{

constexpr double half_angle = 2.5 * M_PI / 180; // each wedge leans 2.5 degrees

//! A 4 x 2 x 1 wedge about the x axis between radii 0.5 and 1: block w runs over the angle
//! -2.5..+2.5 degrees from the x-y plane, so zMin and zMax (type `wedge` unless `lone`:
//! then zMax is a plain patch) lean 2.5 degrees from it. `lean` moves the zMax side this
//! far along x (the wedges stay planar; the edges across the wedge tilt).
PolyMesh x_axis_wedge(double lean = 0, bool lone = false)
{
    return test::make_block_mesh(
        4, 2, 1,
        [lean](double u, double v, double w)
        {
            const double r = 0.5 + 0.5 * v, phi = (2 * w - 1) * half_angle;
            return Vector3(u + lean * w, r * std::cos(phi), r * std::sin(phi));
        },
        {"patch", "patch", "patch", "patch", "wedge", lone ? "patch" : "wedge"});
}

//! The same wedge about the z axis, leaning from the x-z plane (as reactingFoam's DLR).
PolyMesh z_axis_wedge()
{
    return test::make_block_mesh(4, 2, 1,
                                 [](double u, double v, double w)
                                 {
                                     const double r = 0.5 + 0.5 * v, phi = (2 * w - 1) * half_angle;
                                     return Vector3(r * std::cos(phi), r * std::sin(phi), u);
                                 },
                                 {"patch", "patch", "patch", "patch", "wedge", "wedge"});
}

const CheckResult& check_of(const QualityReport& r, CheckId id)
{
    for (const CheckResult& c : r.checks)
        if (c.id == id)
            return c;
    throw std::logic_error("no check " + std::string(check_name(id)));
}

} // namespace

TEST(WedgeGeometry, centre_normal_angle_and_axis)
{
    const PolyMesh mesh = x_axis_wedge();
    const std::vector<WedgeGeometry> wedges = wedge_geometries(mesh);
    ASSERT_EQ(wedges.size(), 2u);
    EXPECT_EQ(wedges[0].patch, 4);
    EXPECT_EQ(wedges[1].patch, 5);
    const double s = std::sin(half_angle), c = std::cos(half_angle);
    // zMin's outward normal leans from -z towards -y, zMax's from +z towards -y.
    EXPECT_TRUE(wedges[0].normal.isApprox(Vector3(0, -s, -c), 1e-14)) << wedges[0].normal;
    EXPECT_TRUE(wedges[1].normal.isApprox(Vector3(0, -s, c), 1e-14)) << wedges[1].normal;
    // The centre normal is the coordinate plane's: the 0.0436 in y is no direction of it.
    EXPECT_EQ(wedges[0].centre_normal, Vector3(0, 0, -1));
    EXPECT_EQ(wedges[1].centre_normal, Vector3(0, 0, 1));
    for (const WedgeGeometry& w : wedges)
    {
        EXPECT_NEAR(std::acos(w.cos_angle), half_angle, 1e-12);
        EXPECT_NEAR(std::abs(w.axis.x()), 1.0, 1e-15);
        EXPECT_NEAR(w.axis.y(), 0.0, 1e-15);
        EXPECT_NEAR(w.axis.z(), 0.0, 1e-15);
    }
    EXPECT_EQ(opposite_wedge(mesh, wedges, 0), 1);
    EXPECT_EQ(opposite_wedge(mesh, wedges, 1), 0);
}

TEST(WedgeGeometry, directions_drop_only_the_centre_normal_direction)
{
    const PolyMesh x_mesh = x_axis_wedge();
    const MeshDirections x_dirs = mesh_directions(x_mesh, compute_geometry(x_mesh).face_areas);
    EXPECT_EQ(x_dirs.geometric, Eigen::Vector3i(1, 1, -1));
    EXPECT_EQ(x_dirs.solution, Eigen::Vector3i(1, 1, 1));
    EXPECT_EQ(x_dirs.n_geometric(), 2);
    EXPECT_TRUE(x_dirs.has_wedges);

    const PolyMesh z_mesh = z_axis_wedge();
    const MeshDirections z_dirs = mesh_directions(z_mesh, compute_geometry(z_mesh).face_areas);
    EXPECT_EQ(z_dirs.geometric, Eigen::Vector3i(1, -1, 1));
    const std::vector<WedgeGeometry> wedges = wedge_geometries(z_mesh);
    ASSERT_EQ(wedges.size(), 2u);
    EXPECT_NEAR(std::abs(wedges[0].axis.z()), 1.0, 1e-15);
}

TEST(WedgeCheck, sound_wedge_reports_its_angles_and_passes)
{
    const PolyMesh mesh = x_axis_wedge();
    const QualityReport r = check_mesh(mesh, CheckMeshSettings{});
    const std::string expected = "    Mesh has 2 geometric (non-empty/wedge) directions (1 1 0)\n"
                                 "    Mesh has 3 solution (non-empty) directions (1 1 1)\n"
                                 "    Wedge zMin with angle 2.5 degrees\n"
                                 "    Wedge zMax with angle 2.5 degrees\n"
                                 "    All edges aligned with or perpendicular to non-empty "
                                 "directions.\n"
                                 "    Boundary openness";
    EXPECT_NE(r.text.find(expected), std::string::npos) << r.text;
    EXPECT_TRUE(r.mesh_ok()) << r.text;
    const CheckResult& c = check_of(r, CheckId::wedges);
    EXPECT_FALSE(c.failed());
    EXPECT_EQ(c.count("nonAlignedEdges"), 0);
    const nlohmann::json j = quality_json(r);
    EXPECT_NEAR(j["wedgeAngles"]["zMax"].get<double>(), 2.5, 1e-12);
}

TEST(WedgeCheck, edges_leaning_across_the_wedge_fail_edge_alignment)
{
    const PolyMesh mesh = x_axis_wedge(0.01);
    const std::vector<WedgeGeometry> wedges = wedge_geometries(mesh);
    const MeshDirections dirs = mesh_directions(mesh, compute_geometry(mesh).face_areas, wedges);
    EXPECT_EQ(dirs.geometric, Eigen::Vector3i(1, 1, -1));
    const WedgeFindings found = wedge_findings(mesh, wedges, dirs);
    EXPECT_EQ(found.problem, WedgeFindings::Problem::none);
    EXPECT_EQ(found.n_examined, 2u);
    // One edge across the wedge at each of the 5 x 3 block points; the wedges' own edges,
    // in the leaning planes, are exempt.
    EXPECT_EQ(found.non_aligned.size(), 15u);
    const CheckResult c = check_wedges(mesh, wedges, found);
    EXPECT_EQ(c.failure, "edgeAlignment");
    ASSERT_EQ(c.sets.size(), 1u);
    EXPECT_EQ(c.sets[0].set.name, "nonAlignedEdges");
    EXPECT_EQ(c.sets[0].set.labels.size(), 30u);
    const QualityReport r = check_mesh(mesh, CheckMeshSettings{});
    EXPECT_NE(r.text.find("    Wedge zMax with angle 2.5 degrees\n ***Number of edges not "
                          "aligned with or perpendicular to non-empty directions: 15\n"),
              std::string::npos)
        << r.text;
    EXPECT_EQ(r.failed_check_names, std::vector<std::string>{"edgeAlignment"});
}

TEST(WedgeCheck, a_wedge_without_opposite_stops_the_check)
{
    const PolyMesh mesh = x_axis_wedge(0, true);
    const std::vector<WedgeGeometry> wedges = wedge_geometries(mesh);
    ASSERT_EQ(wedges.size(), 1u);
    EXPECT_EQ(opposite_wedge(mesh, wedges, 0), -1);
    const QualityReport r = check_mesh(mesh, CheckMeshSettings{});
    EXPECT_NE(r.text.find("    Wedge zMin with angle 2.5 degrees\n ***Cannot find opposite "
                          "wedge for wedge zMin\n    Boundary openness"),
              std::string::npos)
        << r.text;
    EXPECT_EQ(r.failed_check_names, std::vector<std::string>{"wedgeOpposite"});
}

TEST(WedgeCheck, a_point_off_the_wedge_plane_is_reported)
{
    PolyMesh mesh = x_axis_wedge();
    // Point (i, j, k) = (2, 1, 1): the middle of zMax, moved 1e-4 off its plane.
    const Index p = 2 + 5 * (1 + 3 * 1);
    const Vector3 normal(0, -std::sin(half_angle), std::cos(half_angle));
    mesh.points.row(p) += 1e-4 * normal.transpose();
    const std::vector<WedgeGeometry> wedges = wedge_geometries(mesh);
    const WedgeFindings found =
        wedge_findings(mesh, wedges, mesh_directions(mesh, compute_geometry(mesh).face_areas));
    ASSERT_EQ(found.problem, WedgeFindings::Problem::not_planar);
    EXPECT_EQ(found.n_examined, 2u); // zMin is sound; zMax fails
    EXPECT_GT(found.off_plane_distance, std::sqrt(constants::small));
    const QualityReport r = check_mesh(mesh, CheckMeshSettings{});
    EXPECT_NE(r.text.find(" ***Wedge patch zMax not planar. Point ("), std::string::npos) << r.text;
    EXPECT_EQ(r.failed_check_names, std::vector<std::string>{"wedgePlanarity"});
}
