// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of src/meshmorph/morph/: patch matching, conflicts, handles, 2D rules.
#include "meshmorph/morph/constraints.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_dictionary.h"

namespace meshmorph::morph
{
namespace
{

BoundaryEntry entry(const std::string& key, MotionType type, bool regex = false,
                    std::size_t line = 0)
{
    BoundaryEntry e;
    e.key = key;
    e.is_regex = regex;
    e.motion.type = type;
    e.line = line;
    return e;
}

BoundaryEntry translate(const std::string& key, const Vector3& v, bool regex = false)
{
    BoundaryEntry e = entry(key, MotionType::translate, regex);
    e.motion.vector = v;
    return e;
}

//! Index of point p in c.points, or -1.
Index find_constraint(const Constraints& c, Index p)
{
    auto it = std::lower_bound(c.points.begin(), c.points.end(), p);
    return (it != c.points.end() && *it == p) ? static_cast<Index>(it - c.points.begin()) : -1;
}

std::vector<char> on_patch(const PolyMesh& mesh, const std::string& name)
{
    std::vector<char> mask(mesh.n_points(), 0);
    for (Index p : patch_points(mesh, mesh.patches[mesh.find_patch(name)]))
        mask[p] = 1;
    return mask;
}

TEST(MorphSetup, unlisted_patches_are_fixed_and_interior_points_unconstrained)
{
    const PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    const Constraints c = build_constraints(mesh, MorphSetup{});
    const std::vector<char> boundary = boundary_point_mask(mesh);
    Index n_boundary = 0;
    for (char b : boundary)
        n_boundary += b;
    ASSERT_EQ(static_cast<Index>(c.points.size()), n_boundary);
    for (Index p : c.points)
        EXPECT_TRUE(boundary[p]);
    EXPECT_EQ(c.displacements.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(c.n_conflicts, 0);
}

TEST(MorphSetup, translated_patch_and_fixed_rest_conflict_on_shared_edges)
{
    const PolyMesh mesh = test::make_box_mesh(4, 4, 4);
    MorphSetup setup;
    setup.boundary.push_back(translate("zMax", Vector3(0, 0, 0.1)));
    const Constraints c = build_constraints(mesh, setup);
    const std::vector<char> top = on_patch(mesh, "zMax");
    const std::vector<char> sides = on_patch(mesh, "xMin");
    Index expected_conflicts = 0;
    for (Index p = 0; p < mesh.n_points(); ++p)
    {
        const bool side = on_patch(mesh, "xMin")[p] || on_patch(mesh, "xMax")[p] ||
                          on_patch(mesh, "yMin")[p] || on_patch(mesh, "yMax")[p];
        if (top[p] && side)
            ++expected_conflicts;
    }
    EXPECT_EQ(c.n_conflicts, expected_conflicts);
    ASSERT_FALSE(c.conflict_summary.empty());
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        const Index p = c.points[i];
        const bool side = on_patch(mesh, "xMin")[p] || on_patch(mesh, "xMax")[p] ||
                          on_patch(mesh, "yMin")[p] || on_patch(mesh, "yMax")[p];
        const Vector3 d = c.displacements.row(static_cast<Eigen::Index>(i)).transpose();
        if (top[p] && !side)
            EXPECT_EQ(d, Vector3(0, 0, 0.1));
        else
            EXPECT_EQ(d, Vector3::Zero()) << "default rule 'fixed' holds shared points";
    }
    (void)sides;
}

TEST(MorphSetup, conflict_rules_first_last_average_and_error)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    MorphSetup setup;
    setup.boundary.push_back(translate("xMax", Vector3(0.1, 0, 0)));
    setup.boundary.push_back(translate("zMax", Vector3(0, 0, 0.2)));
    setup.boundary.push_back(translate("default", Vector3(0, 0, 0)));
    // Point (1, 0.5, 1) lies on xMax and zMax only.
    const Index p = 2 + 3 * (1 + 3 * 2);
    ASSERT_TRUE(mesh.points.row(p).isApprox(Eigen::RowVector3d(1, 0.5, 1)));

    const auto value = [&](ConflictRule rule)
    {
        setup.conflicts = rule;
        const Constraints c = build_constraints(mesh, setup);
        const Index i = find_constraint(c, p);
        EXPECT_GE(i, 0);
        return Vector3(c.displacements.row(i).transpose());
    };
    EXPECT_EQ(value(ConflictRule::first), Vector3(0.1, 0, 0));
    EXPECT_EQ(value(ConflictRule::last), Vector3(0, 0, 0.2));
    EXPECT_TRUE(value(ConflictRule::average).isApprox(Vector3(0.05, 0, 0.1)));
    EXPECT_EQ(value(ConflictRule::fixed), Vector3::Zero());

    setup.conflicts = ConflictRule::error;
    try
    {
        build_constraints(mesh, setup);
        FAIL() << "conflicts error must throw";
    }
    catch (const InvalidInput& e)
    {
        const std::string what = e.what();
        EXPECT_NE(what.find("system/morphDict"), std::string::npos) << what;
        EXPECT_NE(what.find("xMax/zMax"), std::string::npos) << what;
    }
}

TEST(MorphSetup, equal_prescriptions_on_shared_points_are_no_conflict)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    MorphSetup setup;
    setup.boundary.push_back(translate("default", Vector3(0.3, 0.2, 0.1)));
    const Constraints c = build_constraints(mesh, setup);
    EXPECT_EQ(c.n_conflicts, 0);
    for (Eigen::Index i = 0; i < c.displacements.rows(); ++i)
        EXPECT_EQ(Vector3(c.displacements.row(i).transpose()), Vector3(0.3, 0.2, 0.1));
}

TEST(MorphSetup, name_beats_group_beats_regex_beats_default)
{
    const PolyMesh mesh = test::make_block_mesh(
        2, 2, 2, [](double u, double v, double w) { return Vector3(u, v, w); },
        {"wall", "wall", "patch", "patch", "patch", "patch"});
    MorphSetup setup;
    setup.boundary.push_back(entry("x.*", MotionType::free, true));
    setup.boundary.push_back(entry("wall", MotionType::slip));
    setup.boundary.push_back(entry("xMax", MotionType::fixed));
    setup.boundary.push_back(entry("y.*", MotionType::free, true));
    const std::vector<PatchAssignment> a = assign_patches(mesh, setup);
    EXPECT_EQ(a[0].matched_by, "group wall");
    EXPECT_EQ(a[0].motion, MotionType::slip);
    EXPECT_EQ(a[1].matched_by, "name");
    EXPECT_EQ(a[1].motion, MotionType::fixed);
    EXPECT_EQ(a[2].matched_by, "regex \"y.*\"");
    EXPECT_EQ(a[4].matched_by, "default (fixed)");
}

TEST(MorphSetup, unknown_patch_and_empty_regex_name_file_and_line)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    for (const BoundaryEntry& bad : {entry("wing", MotionType::fixed, false, 17),
                                     entry("motorBike_.*", MotionType::fixed, true, 17)})
    {
        MorphSetup setup;
        setup.dict_path = "case/system/morphDict";
        setup.boundary.push_back(bad);
        try
        {
            build_constraints(mesh, setup);
            FAIL() << "expected a ParseError for " << bad.key;
        }
        catch (const ParseError& e)
        {
            EXPECT_EQ(e.path(), "case/system/morphDict");
            EXPECT_EQ(e.line(), 17u);
            EXPECT_NE(std::string(e.what()).find(bad.key), std::string::npos) << e.what();
        }
    }
}

TEST(MorphSetup, processor_patches_outside_a_parallel_run_are_refused)
{
    PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    mesh.patches[0].type = "processor";
    try
    {
        build_constraints(mesh, MorphSetup{});
        FAIL();
    }
    catch (const InvalidInput& e)
    {
        EXPECT_NE(std::string(e.what()).find("run morphMesh -parallel"), std::string::npos)
            << e.what();
    }
}

TEST(MorphSetup, empty_planes_refuse_normal_motion_and_explicit_entries)
{
    const PolyMesh mesh = test::make_block_mesh(
        3, 3, 1, [](double u, double v, double w) { return Vector3(u, v, 0.1 * w); },
        {"patch", "patch", "patch", "patch", "empty", "empty"});
    MorphSetup setup;
    // A motion with a part normal to the planes would be dropped: an error naming the entry.
    setup.boundary.push_back(translate("yMax", Vector3(0.1, 0.2, 0.3)));
    EXPECT_THROW(build_constraints(mesh, setup), ParseError);
    setup.boundary.back() = translate("yMax", Vector3(0.1, 0.2, 0.0));
    const Constraints c = build_constraints(mesh, setup);
    ASSERT_TRUE(c.empty_planes.has_value());
    EXPECT_NEAR(std::abs(c.empty_planes->normal.z()), 1.0, 1e-15);
    EXPECT_EQ(c.displacements.col(2).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_NEAR(c.displacements.col(1).maxCoeff(), 0.2, 1e-15);

    setup.boundary.push_back(entry("zMin", MotionType::fixed, false, 9));
    EXPECT_THROW(build_constraints(mesh, setup), ParseError);
}

TEST(MorphSetup, points_handle_in_a_2d_case_moves_the_pair_on_both_empty_planes)
{
    const PolyMesh mesh = test::make_block_mesh(
        4, 4, 1, [](double u, double v, double w) { return Vector3(u, v, 0.1 * w); },
        {"patch", "patch", "patch", "patch", "empty", "empty"});
    MorphSetup setup;
    HandleEntry h;
    h.name = "pt";
    h.selection = HandleEntry::Selection::points;
    h.points = Points(1, 3);
    h.points.row(0) << 0.49, 0.51, 0.03; // nearest to (0.5 0.5), closer to the z = 0 plane
    h.displacement = Vector3(0.01, 0.02, 0.0);
    setup.handles.push_back(h);
    const Constraints c = build_constraints(mesh, setup);
    std::vector<Vector3> moved;
    for (std::size_t i = 0; i < c.points.size(); ++i)
        if (c.displacements.row(static_cast<Eigen::Index>(i)).norm() > 0.0)
            moved.push_back(mesh.points.row(c.points[i]).transpose());
    ASSERT_EQ(moved.size(), 2u) << "one point on each empty plane";
    EXPECT_EQ(moved[0].head<2>(), Vector3(0.5, 0.5, 0).head<2>());
    EXPECT_EQ(moved[1].head<2>(), moved[0].head<2>());
    EXPECT_NE(moved[0].z(), moved[1].z());
    EXPECT_EQ(c.n_handle_points, 2);
}

TEST(MorphSetup, slip_patch_gets_projector_of_its_plane_and_curved_patch_is_refused)
{
    const PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    MorphSetup setup;
    setup.boundary.push_back(entry("zMin", MotionType::slip));
    setup.boundary.push_back(entry("default", MotionType::free));
    const Constraints c = build_constraints(mesh, setup);
    EXPECT_TRUE(c.points.empty());
    ASSERT_EQ(c.slip_points.size(), 16u);
    for (const Eigen::Matrix3d& P : c.slip_projectors)
        EXPECT_TRUE(P.isApprox(Eigen::Vector3d(1, 1, 0).asDiagonal().toDenseMatrix(), 1e-14));

    const PolyMesh bent =
        test::make_block_mesh(4, 4, 4,
                              [](double u, double v, double w)
                              { return Vector3(u, v, w + 0.2 * std::sin(std::numbers::pi * u)); });
    setup.boundary[0].line = 5;
    try
    {
        build_constraints(bent, setup);
        FAIL();
    }
    catch (const ParseError& e)
    {
        EXPECT_EQ(e.line(), 5u);
        EXPECT_NE(std::string(e.what()).find("not planar"), std::string::npos);
    }
}

TEST(MorphSetup, rotate_and_scale_are_the_rigid_and_affine_maps)
{
    Motion rotate;
    rotate.type = MotionType::rotate;
    rotate.origin = Vector3(1, 0, 0);
    rotate.axis = Vector3(0, 0, 2);
    rotate.angle_degrees = 90;
    const Vector3 d = rotate.displacement(Vector3(2, 0, 5));
    EXPECT_TRUE((Vector3(2, 0, 5) + d).isApprox(Vector3(1, 1, 5), 1e-14));

    Motion scale;
    scale.type = MotionType::scale;
    scale.origin = Vector3(0, 0, 1);
    scale.factor = Vector3(0.7, 0.7, 1);
    EXPECT_TRUE((Vector3(1, 2, 3) + scale.displacement(Vector3(1, 2, 3)))
                    .isApprox(Vector3(0.7, 1.4, 3), 1e-14));
}

TEST(MorphSetup, handles_override_boundary_and_report_it)
{
    const PolyMesh mesh = test::make_box_mesh(4, 4, 4);
    MorphSetup setup;
    HandleEntry h;
    h.name = "roof";
    h.selection = HandleEntry::Selection::box;
    h.box_min = Vector3(0.4, 0.4, 0.4);
    h.box_max = Vector3(0.6, 0.6, 1.0);
    h.displacement = Vector3(0, 0, 0.05);
    setup.handles.push_back(h);
    const Constraints c = build_constraints(mesh, setup);
    // x = y = 0.5, z in {0.5, 0.75, 1}: 3 points, one of them on zMax.
    EXPECT_EQ(c.n_handle_points, 3);
    EXPECT_EQ(c.n_handle_overrides, 1);
    const Index top = 2 + 5 * (2 + 5 * 4);
    const Index i = find_constraint(c, top);
    ASSERT_GE(i, 0);
    EXPECT_EQ(Vector3(c.displacements.row(i).transpose()), Vector3(0, 0, 0.05));

    setup.handles[0].selection = HandleEntry::Selection::point_zone;
    setup.handles[0].zone = "roofPoints";
    setup.handles[0].line = 30;
    EXPECT_THROW(build_constraints(mesh, setup), ParseError);

    setup.handles[0].selection = HandleEntry::Selection::points;
    setup.handles[0].points = Points(1, 3);
    setup.handles[0].points << 0.49, 0.51, 0.52;
    const Constraints near = build_constraints(mesh, setup);
    EXPECT_GE(find_constraint(near, 2 + 5 * (2 + 5 * 2)), 0);
    EXPECT_EQ(near.n_handle_points, 1);
}

TEST(MorphSetup, surface_and_point_displacement_take_their_values_from_inputs)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    MorphSetup setup;
    BoundaryEntry s = entry("zMax", MotionType::surface);
    s.motion.file = "target.stl";
    setup.boundary.push_back(s);
    setup.boundary.push_back(entry("zMin", MotionType::point_displacement));
    setup.boundary.push_back(entry("default", MotionType::free));
    EXPECT_THROW(build_constraints(mesh, setup), ParseError); // no inputs given

    Points field = Points::Zero(mesh.n_points(), 3);
    field.col(0).setConstant(-0.01);
    ConstraintInputs inputs;
    inputs.point_displacement = &field;
    inputs.project_to_surface = [](const std::string& file, const Points& q)
    {
        EXPECT_EQ(file, "target.stl");
        Points out = q;
        out.col(2).setConstant(1.25); // the plane z = 1.25
        return out;
    };
    const Constraints c = build_constraints(mesh, setup, inputs);
    EXPECT_EQ(c.points.size(), 18u);
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        const double z = mesh.points(c.points[i], 2);
        const Vector3 d = c.displacements.row(static_cast<Eigen::Index>(i)).transpose();
        if (z == 1.0)
            EXPECT_NEAR(d.z(), 0.25, 1e-15);
        else
            EXPECT_EQ(d, Vector3(-0.01, 0, 0));
    }
}

TEST(MorphSetup, a_motion_within_a_slip_plane_to_its_precision_is_no_conflict)
{
    // movingCone-style: the moving wall slides along the wedge (here slip) planes; the
    // motion as written is in the plane only to a few digits. No conflict, and the shared
    // points move exactly within the plane.
    const PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    MorphSetup setup;
    setup.boundary.push_back(entry("xMin", MotionType::slip));
    setup.boundary.push_back(translate("zMax", Vector3(1e-9, 0.0, 0.05)));
    setup.boundary.push_back(entry("default", MotionType::free));
    const Constraints c = build_constraints(mesh, setup);
    EXPECT_EQ(c.n_conflicts, 0) << (c.conflict_summary.empty() ? "" : c.conflict_summary[0]);
    const std::vector<char> slip = on_patch(mesh, "xMin");
    Index shared = 0;
    for (std::size_t i = 0; i < c.points.size(); ++i)
        if (slip[c.points[i]])
        {
            ++shared;
            EXPECT_EQ(c.displacements(Eigen::Index(i), 0), 0.0) << "exactly in the plane x = 0";
            EXPECT_EQ(c.displacements(Eigen::Index(i), 2), 0.05);
        }
    EXPECT_EQ(shared, 4) << "the edge xMin/zMax";

    // A normal component below 10% of the edge (0.01 of 1/3: snapping-sized) is projected
    // into the plane and reported apart from conflicts; a real one is still a conflict.
    setup.boundary[1] = translate("zMax", Vector3(0.01, 0.0, 0.05));
    const Constraints near = build_constraints(mesh, setup);
    EXPECT_EQ(near.n_conflicts, 0);
    EXPECT_EQ(near.n_near_agreements, 4);
    EXPECT_NEAR(near.max_near_agreement, 0.03, 1e-12);
    for (std::size_t i = 0; i < near.points.size(); ++i)
        if (slip[near.points[i]])
        {
            EXPECT_EQ(near.displacements(Eigen::Index(i), 0), 0.0);
            EXPECT_EQ(near.displacements(Eigen::Index(i), 2), 0.05);
        }
    setup.boundary[1] = translate("zMax", Vector3(0.05, 0.0, 0.05));
    EXPECT_EQ(build_constraints(mesh, setup).n_conflicts, 4);
}

TEST(MorphSetup, snapping_sized_disagreements_at_patch_edges_are_no_conflicts)
{
    // A lid lifted by 1% of its edge length next to fixed sides (as a projection onto the
    // STL a snapped patch came from moves its edge points): rule fixed holds the shared
    // points, but they are not reported as conflicts; 20% of the edge is a conflict.
    const PolyMesh mesh = test::make_box_mesh(4, 4, 4);
    MorphSetup setup;
    setup.boundary.push_back(translate("zMax", Vector3(0.0, 0.0, 0.0025)));
    const Constraints small = build_constraints(mesh, setup);
    EXPECT_EQ(small.n_conflicts, 0);
    EXPECT_EQ(small.n_near_agreements, 16) << "the lid's rim: 4 x 4 points";
    EXPECT_NEAR(small.max_near_agreement, 0.01, 1e-12);
    setup.boundary[0] = translate("zMax", Vector3(0.0, 0.0, 0.05));
    const Constraints big = build_constraints(mesh, setup);
    EXPECT_EQ(big.n_conflicts, 16);
    EXPECT_EQ(big.n_near_agreements, 0);
}

TEST(MorphSetup, motion_asked_for_but_resolved_to_nothing_is_an_error)
{
    // One cell: every point of the lid is also on a fixed side, so rule `fixed` holds all.
    const PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    MorphSetup setup;
    setup.dict_path = "system/morphDict";
    setup.boundary.push_back(translate("zMax", Vector3(0.0, 0.0, 0.3)));
    try
    {
        build_constraints(mesh, setup);
        FAIL() << "nothing moves: must not pass quietly";
    }
    catch (const InvalidInput& e)
    {
        const std::string what = e.what();
        EXPECT_NE(what.find("system/morphDict"), std::string::npos) << what;
        EXPECT_NE(what.find("nothing would move"), std::string::npos) << what;
        EXPECT_NE(what.find("conflicts"), std::string::npos) << what;
    }
    setup.conflicts = ConflictRule::last; // the lid wins: it moves
    EXPECT_NO_THROW(build_constraints(mesh, setup));
}

TEST(MorphSetup, a_value_that_is_not_finite_names_its_keyword_and_line)
{
    // It used to name the entry ('zMax', line 4) only: the user had to find the number.
    const std::vector<std::pair<std::string, std::string>> motions = {
        {"type translate;\n        vector (0 nan 0);", "vector"},
        {"type rotate;\n        origin (0 0 0); axis (0 0 1);\n        angle inf;", "angle"},
        {"type scale;\n        origin (0 0 0);\n        factor (1 -inf 1);", "factor"}};
    for (const auto& [motion, keyword] : motions)
    {
        const std::string text = "boundary\n{\n    zMax\n    {\n        " + motion + "\n    }\n}\n";
        try
        {
            read_morph_setup(io::parse_dictionary(text, "system/morphDict"));
            ADD_FAILURE() << motion << " was accepted";
        }
        catch (const ParseError& e)
        {
            const std::string what = e.what();
            EXPECT_NE(what.find("keyword '" + keyword + "'"), std::string::npos) << what;
            EXPECT_NE(what.find("not a finite number"), std::string::npos) << what;
            EXPECT_GT(e.line(), 5u) << what;
        }
    }
}

} // namespace
} // namespace meshmorph::morph
