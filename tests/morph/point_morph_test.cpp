// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of morph_points() (src/meshmorph/morph/point_morph.*): exactness at constraints, fixed
// points, slip planes, 2D cases.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"
#include "meshmorph/morph/constraints.h"
#include "meshmorph/morph/point_morph.h"

namespace meshmorph::morph
{
namespace
{

BoundaryEntry make_entry(const std::string& key, MotionType type)
{
    BoundaryEntry e;
    e.key = key;
    e.motion.type = type;
    return e;
}

//! The constraints of zMax translated by (0.02, 0, 0.1), every other patch fixed.
Constraints top_translated(const PolyMesh& mesh, ConflictRule conflicts)
{
    MorphSetup setup;
    BoundaryEntry top = make_entry("zMax", MotionType::translate);
    top.motion.vector = Vector3(0.02, 0.0, 0.1);
    setup.boundary.push_back(top);
    setup.conflicts = conflicts;
    return build_constraints(mesh, setup);
}

//! A 2D case: n x n cells, one cell thick in z, empty front and back.
PolyMesh two_d_block_mesh(int n)
{
    return test::make_block_mesh(
        n, n, 1, [](double u, double v, double w) { return Vector3(u, v, 0.05 * w - 0.02); },
        {"patch", "patch", "patch", "patch", "empty", "empty"});
}

TEST(MorphPoints, rbf_ends_exactly_at_prescriptions_and_fixed_points_stay)
{
    const PolyMesh mesh = test::make_box_mesh(6, 6, 6);
    const Constraints c = top_translated(mesh, ConflictRule::last); // edges of zMax move with it

    RbfDeformation rbf;
    const PointMorph m = morph_points(mesh, c, rbf);
    EXPECT_EQ(m.n_constraints, static_cast<Index>(c.points.size()));
    EXPECT_LE(m.relative_constraint_error, 1e-9);
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        const Eigen::RowVector3d want = c.displacements.row(static_cast<Eigen::Index>(i));
        const Eigen::RowVector3d got = m.displacement.row(c.points[i]);
        EXPECT_LE((got - want).norm(), 1e-9 * 0.1) << "point " << c.points[i];
        if (want.norm() == 0.0)
        {
            EXPECT_LE(got.norm(), 1e-10);
        }
    }
}

TEST(MorphPoints, snapping_sets_constraints_exactly_and_reports_the_fit_residual)
{
    // A greedy fit with a loose tolerance misses most constraints; snapping must put every
    // constrained point exactly on its prescription, report the pre-snap residual, and
    // leave unconstrained points on the fitted field.
    const PolyMesh mesh = test::make_box_mesh(8, 8, 8);
    MorphSetup setup;
    BoundaryEntry top = make_entry("zMax", MotionType::scale);
    top.motion.origin = Vector3(0.5, 0.5, 0.0);
    top.motion.factor = Vector3(1.2, 0.9, 1.1);
    setup.boundary.push_back(top);
    setup.conflicts = ConflictRule::last;
    const Constraints c = build_constraints(mesh, setup);

    GreedySettings loose;
    loose.tolerance = 0.2;
    loose.rms_tolerance = 0.1;
    GreedyRbfDeformation plain_fit(loose);
    const PointMorph plain = morph_points(mesh, c, plain_fit, true, false);
    GreedyRbfDeformation snapped_fit(loose);
    const PointMorph snapped = morph_points(mesh, c, snapped_fit, true, true);

    ASSERT_GT(plain.relative_fit_residual, 1e-6) << "the loose greedy fit should not be exact";
    EXPECT_FALSE(plain.snapped);
    EXPECT_EQ(plain.max_constraint_error, plain.max_fit_residual);
    EXPECT_TRUE(snapped.snapped);
    EXPECT_EQ(snapped.max_fit_residual, plain.max_fit_residual);
    EXPECT_EQ(snapped.max_constraint_error, 0.0);
    std::vector<char> constrained(static_cast<std::size_t>(mesh.n_points()), 0);
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        constrained[c.points[i]] = 1;
        EXPECT_EQ(snapped.displacement.row(c.points[i]),
                  c.displacements.row(static_cast<Eigen::Index>(i)));
    }
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (!constrained[p])
        {
            EXPECT_EQ(snapped.displacement.row(p), plain.displacement.row(p)) << "point " << p;
        }
}

TEST(MorphPoints, rbf_with_linear_term_reproduces_an_affine_boundary_motion_inside)
{
    // Every patch scaled about one origin: the whole field is affine, and the RBF's linear
    // polynomial must reproduce it at the interior points too (paper Eq. 6).
    const PolyMesh mesh = test::make_box_mesh(5, 4, 6, Vector3(-1, 0, 2), Vector3(1, 3, 4));
    MorphSetup setup;
    BoundaryEntry all = make_entry("default", MotionType::scale);
    all.motion.origin = Vector3(0.1, 0.2, 0.3);
    all.motion.factor = Vector3(0.7, 0.8, 1.1);
    setup.boundary.push_back(all);
    const Constraints c = build_constraints(mesh, setup);
    RbfDeformation rbf;
    const PointMorph m = morph_points(mesh, c, rbf);
    for (Index p = 0; p < mesh.n_points(); ++p)
    {
        const Vector3 want = all.motion.displacement(mesh.points.row(p).transpose());
        EXPECT_LE((m.displacement.row(p).transpose() - want).norm(), 1e-9 * want.norm() + 1e-12)
            << "point " << p;
    }
}

TEST(MorphPoints, slip_points_stay_in_their_plane_and_keep_the_fitted_tangential_motion)
{
    const PolyMesh mesh = test::make_box_mesh(5, 5, 5);
    MorphSetup setup;
    // Rotate the top about the z axis; the bottom slides in z = 0, sides free.
    BoundaryEntry top = make_entry("zMax", MotionType::rotate);
    top.motion.origin = Vector3(0.5, 0.5, 0);
    top.motion.axis = Vector3(0, 0, 1);
    top.motion.angle_degrees = 10;
    setup.boundary.push_back(top);
    setup.boundary.push_back(make_entry("zMin", MotionType::slip));
    setup.boundary.push_back(make_entry("default", MotionType::free));
    BoundaryEntry hold = make_entry("xMin", MotionType::fixed); // something pins the bottom
    setup.boundary.push_back(hold);
    setup.conflicts = ConflictRule::first;
    const Constraints c = build_constraints(mesh, setup);
    ASSERT_FALSE(c.slip_points.empty());

    RbfDeformation rbf;
    const PointMorph m = morph_points(mesh, c, rbf);
    EXPECT_LE(m.relative_constraint_error, 1e-9);
    double max_tangential = 0.0;
    for (Index p : c.slip_points)
    {
        EXPECT_LE(std::abs(m.displacement(p, 2)), 1e-12) << "slip point left z = 0";
        max_tangential = std::max(max_tangential, m.displacement.row(p).norm());
    }
    EXPECT_GT(max_tangential, 1e-3) << "slip points must be free to slide";
}

TEST(MorphPoints, two_d_cases_stay_two_d)
{
    const PolyMesh mesh = two_d_block_mesh(8);
    MorphSetup setup;
    BoundaryEntry top = make_entry("yMax", MotionType::rotate);
    top.motion.origin = Vector3(0.5, 1, 0);
    top.motion.axis = Vector3(1, 1, 1); // not a 2D motion: refused, it would be dropped
    top.motion.angle_degrees = 3;
    setup.boundary.push_back(top);
    setup.conflicts = ConflictRule::last;
    EXPECT_THROW(build_constraints(mesh, setup), ParseError);
    setup.boundary.back().motion.axis = Vector3(0, 0, 1);
    const Constraints c = build_constraints(mesh, setup);

    RbfDeformation rbf;
    const PointMorph m = morph_points(mesh, c, rbf);
    EXPECT_LE(m.relative_constraint_error, 1e-9);
    EXPECT_EQ(m.displacement.col(2).cwiseAbs().maxCoeff(), 0.0);
    const Index layer = 9 * 9;
    for (Index p = 0; p < layer; ++p)
        EXPECT_EQ(m.displacement.row(p), m.displacement.row(p + layer))
            << "front and back planes must move identically";
    EXPECT_GT(m.displacement.cwiseAbs().maxCoeff(), 1e-3);
}

TEST(MorphPoints, near_duplicate_pairs_in_two_d_are_fitted_once)
{
    // pitzDaily's merged block corners leave two point pairs 1e-14 apart whose prescriptions
    // differ by round-off: the fit must see one handle there, not two that coincide.
    PolyMesh mesh = test::make_block_mesh(
        4, 4, 1, [](double u, double v, double w) { return Vector3(u, v, 0.1 * w); },
        {"patch", "patch", "patch", "patch", "empty", "empty"});
    MorphSetup setup;
    BoundaryEntry top = make_entry("yMax", MotionType::translate);
    top.motion.vector = Vector3(0.01, 0.02, 0);
    setup.boundary.push_back(top);
    Constraints c = build_constraints(mesh, setup);
    // Two extra points (front and back) a round-off away from the pair of constrained
    // point 0 (position (0, 0, z)), with a value a round-off away from its value (zero).
    const Index n = mesh.n_points();
    mesh.points.conservativeResize(n + 2, 3);
    mesh.points.row(n) = Vector3(1.4e-14, 0, 0).transpose();
    mesh.points.row(n + 1) = Vector3(1.4e-14, 0, 0.1).transpose();
    ASSERT_EQ(c.points.front(), 0);
    c.points.push_back(n);
    c.points.push_back(n + 1);
    c.rotation_of.resize(c.points.size(), -1);
    c.displacements.conservativeResize(c.displacements.rows() + 2, 3);
    c.displacements.bottomRows(2).setConstant(2e-16);

    RbfDeformation rbf;
    const PointMorph m = morph_points(mesh, c, rbf);
    EXPECT_LE(m.max_constraint_error, 1e-12);
    EXPECT_LE((m.displacement.row(0) - m.displacement.row(n)).norm(), 1e-14);
    EXPECT_GT(m.displacement.cwiseAbs().maxCoeff(), 1e-3);
}

TEST(MorphPoints, zero_prescriptions_are_the_identity)
{
    const PolyMesh mesh = test::make_box_mesh(3, 4, 5);
    const Constraints c = build_constraints(mesh, MorphSetup{});
    RbfDeformation rbf;
    const PointMorph m = morph_points(mesh, c, rbf);
    EXPECT_LE(m.displacement.cwiseAbs().maxCoeff(), 1e-15);
}

TEST(MorphPoints, nothing_prescribed_is_an_error)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    MorphSetup setup;
    setup.boundary.push_back(make_entry("default", MotionType::free));
    const Constraints c = build_constraints(mesh, setup);
    RbfDeformation rbf;
    EXPECT_THROW(morph_points(mesh, c, rbf), InvalidInput);
}

//! <morph(H + delta) - morph(H - delta), G> / 2 for the constraints c with values H: a
//! central difference of J = <d, G> along delta (exact for a linear field).
double central_difference(const PolyMesh& mesh, const Constraints& c, const Points& delta,
                          const Points& G)
{
    double j[2];
    for (const int sign : {1, -1})
    {
        Constraints moved = c;
        moved.displacements += sign * delta;
        RbfDeformation rbf;
        j[sign > 0 ? 0 : 1] =
            (morph_points(mesh, moved, rbf).displacement.array() * G.array()).sum();
    }
    return (j[0] - j[1]) / 2.0;
}

//! The rows of a per-point array at the constrained points (c.points' order), checking that
//! every other row is zero.
Points at_constraints(const Constraints& c, const Points& per_point)
{
    Points rows(Eigen::Index(c.points.size()), 3);
    Points rest = per_point;
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        rows.row(Eigen::Index(i)) = per_point.row(c.points[i]);
        rest.row(c.points[i]).setZero();
    }
    EXPECT_EQ(rest.cwiseAbs().maxCoeff(), 0.0) << "nonzero where nothing is prescribed";
    return rows;
}

//! A fresh direct RBF (linear in its data: central differences of it are exact).
std::unique_ptr<SpaceDeformation> direct_rbf()
{
    return std::make_unique<RbfDeformation>();
}

//! dJ/dH of morph_points_transpose (random dJ/dx, a direct RBF) at c's constrained points,
//! checked against a central difference along a random perturbation of the prescriptions:
//! the field is linear, so they agree to the solve's round-off (1e-9 of the terms' sum).
Points transpose_against_differences(const PolyMesh& mesh, const Constraints& c)
{
    const Points G = Points::Random(mesh.n_points(), 3);
    const Points A = at_constraints(c, morph_points_transpose(mesh, c, direct_rbf, G));
    const Points delta = 0.01 * Points::Random(A.rows(), 3);
    EXPECT_NEAR(central_difference(mesh, c, delta, G), (A.array() * delta.array()).sum(),
                1e-9 * (A.array().abs() * delta.array().abs()).sum());
    return A;
}

TEST(MorphPoints, the_transpose_gives_dJ_dH_as_central_differences_do)
{
    const PolyMesh mesh = test::make_box_mesh(5, 5, 5);
    transpose_against_differences(mesh, top_translated(mesh, MorphSetup{}.conflicts));
}

TEST(MorphPoints, the_transpose_through_slip_points_gives_what_central_differences_give)
{
    // The slip points' prescriptions come from a first fit (the field there, projected onto
    // their plane), so dJ/dH reaches the constrained points through them too.
    const PolyMesh mesh = test::make_box_mesh(5, 5, 5);
    MorphSetup setup;
    BoundaryEntry top = make_entry("zMax", MotionType::translate);
    top.motion.vector = Vector3(0.02, 0.03, 0.1);
    setup.boundary.push_back(top);
    setup.boundary.push_back(make_entry("xMin", MotionType::slip));
    const Constraints c = build_constraints(mesh, setup);
    ASSERT_FALSE(c.slip_points.empty());
    transpose_against_differences(mesh, c);
}

TEST(MorphPoints, the_transpose_in_two_d_drops_what_the_morph_drops)
{
    // Front and back points fitted as one handle at their mean, normal components removed:
    // a perturbation of one point of a pair moves the pair by half of it.
    const PolyMesh mesh = two_d_block_mesh(6);
    MorphSetup setup;
    BoundaryEntry top = make_entry("yMax", MotionType::translate);
    top.motion.vector = Vector3(0.02, 0.05, 0.0);
    setup.boundary.push_back(top);
    const Constraints c = build_constraints(mesh, setup);
    ASSERT_TRUE(c.empty_planes.has_value());
    const Points A = transpose_against_differences(mesh, c);
    EXPECT_EQ(A.col(2).cwiseAbs().maxCoeff(), 0.0) << "a normal prescription is dropped";
}

} // namespace
} // namespace meshmorph::morph
