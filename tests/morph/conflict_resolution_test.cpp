// SPDX-License-Identifier: GPL-3.0-or-later
// resolve() (src/meshmorph/morph/conflict_resolution.*) on hand-made claims: agreement,
// every conflict rule, slip planes, near agreements; and the empty planes of 2D cases.
#include "meshmorph/morph/conflict_resolution.h"

#include <gtest/gtest.h>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/morph/empty_planes.h"

namespace meshmorph::morph
{
namespace
{

Claim value(Index point, Index source, const Vector3& v)
{
    return {point, source, source, Claim::Kind::value, v};
}

Claim slip(Index point, Index source, const Vector3& normal)
{
    return {point, source, source, Claim::Kind::slip, normal};
}

ResolveSettings settings(ConflictRule rule)
{
    ResolveSettings s;
    s.rule = rule;
    s.agree_tolerance = 1e-12;
    s.in_plane_tolerance = 1e-5;
    s.conflict_name = [](const std::vector<const Claim*>& claims)
    {
        std::string name;
        for (const Claim* c : claims)
            name += std::to_string(c->source);
        return name;
    };
    return s;
}

// Point 0: two agreeing values; point 1: values (1 0 0) from source 0, (0 1 0) from source 1;
// point 2: a free claim only.
std::vector<Claim> two_conflicting_values()
{
    return {value(0, 0, Vector3(1, 2, 3)),
            value(0, 1, Vector3(1, 2, 3)),
            value(1, 0, Vector3(1, 0, 0)),
            value(1, 1, Vector3(0, 1, 0)),
            {2, 0, 0, Claim::Kind::free, Vector3::Zero()}};
}

TEST(Resolve, agreeing_claims_give_their_value_and_free_points_are_counted)
{
    const Resolution r = resolve(two_conflicting_values(), settings(ConflictRule::fixed));
    ASSERT_EQ(r.points.size(), 2u);
    EXPECT_EQ(r.points[0].point, 0);
    EXPECT_EQ(r.points[0].value, Vector3(1, 2, 3));
    EXPECT_EQ(r.n_free, 1);
    EXPECT_EQ(r.n_conflicts, 1);
    ASSERT_EQ(r.conflict_summary().size(), 1u);
    EXPECT_EQ(r.conflict_summary()[0], "01: 1 points");
}

TEST(Resolve, every_rule_decides_a_conflict)
{
    const std::vector<Claim> claims = two_conflicting_values();
    EXPECT_EQ(resolve(claims, settings(ConflictRule::fixed)).points[1].value, Vector3::Zero());
    EXPECT_EQ(resolve(claims, settings(ConflictRule::error)).points[1].value, Vector3::Zero());
    EXPECT_EQ(resolve(claims, settings(ConflictRule::first)).points[1].value, Vector3(1, 0, 0));
    EXPECT_EQ(resolve(claims, settings(ConflictRule::last)).points[1].value, Vector3(0, 1, 0));
    EXPECT_EQ(resolve(claims, settings(ConflictRule::average)).points[1].value,
              Vector3(0.5, 0.5, 0));
}

TEST(Resolve, a_value_in_the_slip_plane_agrees_and_one_across_it_conflicts)
{
    const Vector3 z = Vector3::UnitZ();
    const std::vector<Claim> claims = {value(0, 0, Vector3(1, 1, 0)),
                                       slip(0, 1, z),
                                       value(1, 0, Vector3(1, 1, 1)),
                                       slip(1, 1, z),
                                       slip(2, 0, z),
                                       slip(2, 1, Vector3::UnitX())};
    const Resolution r = resolve(claims, settings(ConflictRule::last));
    ASSERT_EQ(r.points.size(), 3u);
    EXPECT_FALSE(r.points[0].is_slip);
    EXPECT_EQ(r.points[0].value, Vector3(1, 1, 0));
    EXPECT_TRUE(r.points[1].is_slip) << "rule last: the slip entry is written last";
    EXPECT_EQ(r.n_conflicts, 1);
    // Two planes: the point slides along their intersection (the y axis).
    ASSERT_TRUE(r.points[2].is_slip);
    EXPECT_NEAR((r.points[2].projector * Vector3(1, 1, 1) - Vector3(0, 1, 0)).norm(), 0, 1e-15);
}

TEST(Resolve, differences_below_a_tenth_of_the_shortest_edge_are_near_agreements)
{
    const std::vector<double> edges = {1.0, 1.0};
    ResolveSettings s = settings(ConflictRule::fixed);
    s.shortest_edges = &edges;
    // Point 0: 0.05 off the slip plane (near: projected into it); point 1: values 0.5 apart.
    const std::vector<Claim> claims = {value(0, 0, Vector3(1, 0, 0.05)),
                                       slip(0, 1, Vector3::UnitZ()), value(1, 0, Vector3(1, 0, 0)),
                                       value(1, 1, Vector3(1.5, 0, 0))};
    const Resolution r = resolve(claims, s);
    EXPECT_EQ(r.n_near_agreements, 1);
    EXPECT_DOUBLE_EQ(r.max_near_agreement, 0.05);
    EXPECT_EQ(r.n_conflicts, 1);
    EXPECT_NEAR((r.points[0].value - Vector3(1, 0, 0)).norm(), 0, 1e-15);
    EXPECT_EQ(r.points[1].value, Vector3::Zero());
}

TEST(EmptyPlanes, found_from_the_empty_patches_and_used_to_project)
{
    const PolyMesh mesh = test::make_block_mesh(
        3, 3, 1, [](double u, double v, double w) { return Vector3(u, v, 0.2 * w + 1); },
        {"patch", "patch", "patch", "patch", "empty", "empty"});
    const std::optional<EmptyPlanes> planes = find_empty_planes(mesh);
    ASSERT_TRUE(planes.has_value());
    EXPECT_EQ(planes->normal.cwiseAbs(), Vector3::UnitZ());
    const Vector3 on_plane = planes->project(Vector3(0.3, 0.4, 7));
    EXPECT_EQ(on_plane.head<2>(), Eigen::Vector2d(0.3, 0.4));
    EXPECT_TRUE(on_plane.z() == 1.0 || on_plane.z() == 1.2) << on_plane.z();
    EXPECT_EQ(planes->in_plane(Vector3(1, 2, 3)), Vector3(1, 2, 0));
    EXPECT_FALSE(find_empty_planes(test::make_box_mesh(2, 2, 2)).has_value());
}

TEST(EmptyPlanes, planes_that_are_not_parallel_are_an_error)
{
    const PolyMesh mesh = test::make_block_mesh(
        2, 2, 2, [](double u, double v, double w) { return Vector3(u, v, w); },
        {"empty", "patch", "patch", "patch", "empty", "patch"});
    EXPECT_THROW(find_empty_planes(mesh), InvalidInput);
}

} // namespace
} // namespace meshmorph::morph
