// SPDX-License-Identifier: GPL-3.0-or-later
// A coarse greedy RBF made exact by the IDW correction of its residual
// (src/meshmorph/deform/corrected_deformation.*).
#include <gtest/gtest.h>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/corrected_deformation.h"
#include "meshmorph/deform/field_io.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph
{

TEST(CorrectedDeformation, a_coarse_greedy_fit_becomes_exact_with_a_bounded_correction)
{
    const Points x = test::sphere_points(3000, Vector3(0.5, 0.5, 0.5), 0.5);
    const Points d = test::smooth_field(x);
    GreedySettings coarse;
    coarse.tolerance = 0.1; // far from exact on purpose
    coarse.rms_tolerance = 0.1;
    auto global = std::make_unique<GreedyRbfDeformation>(coarse);
    const GreedyRbfDeformation& g = *global;
    IdwSettings direct_sum; // theta 0: the correction exactly a convex combination
    direct_sum.theta = 0.0;
    CorrectedDeformation corrected(std::move(global), direct_sum);
    corrected.fit(x, d);
    const double max_d = test::max_norm(d);
    EXPECT_GT(g.report().max_residual, 1e-3 * max_d) << "the global part alone is not exact";
    EXPECT_EQ(corrected.report().max_residual, g.report().max_residual);

    // Exact at every constraint (the global value plus exactly its residual).
    const Points at_handles = displacements(corrected, x);
    EXPECT_LE((at_handles - d).rowwise().norm().maxCoeff(), 1e-15 * max_d + 1e-16);

    // Everywhere else the correction is a convex combination of residuals: never larger
    // than the largest one.
    const Points probe = test::random_points(2000, -0.2, 1.2, 3);
    const Points total = displacements(corrected, probe);
    const Points coarse_only = displacements(g, probe);
    const double correction = (total - coarse_only).rowwise().norm().maxCoeff();
    EXPECT_LE(correction, corrected.report().max_residual * (1.0 + 1e-12));
}

TEST(CorrectedDeformation, a_direct_rbf_on_nearly_coincident_constraints_falls_back_to_greedy)
{
    // Constraints in wall-resolved layers: pairs 1e-9 apart (as where a wall-resolved inlet
    // meets a wall), which make the triharmonic system singular in double precision.
    const Points base = test::sphere_points(400, Vector3(0.5, 0.5, 0.5), 0.5);
    Points x(2 * base.rows(), 3);
    x << base, base.rowwise() + Eigen::RowVector3d(1e-9, 0, 0);
    const Points d = test::smooth_field(x);
    RbfDeformation alone;
    EXPECT_THROW(alone.fit(x, d), SolverError) << "the premise: the direct system is singular";
    CorrectedDeformation corrected(std::make_unique<RbfDeformation>());
    corrected.fit(x, d);
    EXPECT_EQ(corrected.report().method, "greedy-rbf+idw");
    const double max_d = test::max_norm(d);
    EXPECT_LE((displacements(corrected, x) - d).rowwise().norm().maxCoeff(), 1e-12 * max_d);
}

namespace
{

//! A ball lifted by `lift` inside a fixed box: the set-up where a global RBF overshoots.
struct LiftedBall
{
    Points x;
    Points d;
    double lift = 0.1;
    LiftedBall()
    {
        const Points ball = test::sphere_points(600, Vector3(0.5, 0.5, 0.35), 0.2);
        Points box = test::random_points(1200, 0.0, 1.0, 11);
        for (Eigen::Index i = 0; i < box.rows(); ++i) // onto the faces of the unit cube
            box(i, i % 3) = (i / 3) % 2 == 0 ? 0.0 : 1.0;
        x.resize(ball.rows() + box.rows(), 3);
        x << ball, box;
        d = Points::Zero(x.rows(), 3);
        d.topRows(ball.rows()).col(2).setConstant(lift);
    }
};

} // namespace

TEST(CorrectedDeformation, the_limit_keeps_every_point_within_the_largest_prescription)
{
    const LiftedBall c;
    CorrectedDeformation raw(std::make_unique<RbfDeformation>());
    CorrectedDeformation limited(std::make_unique<RbfDeformation>(), IdwSettings{}, true);
    raw.fit(c.x, c.d);
    limited.fit(c.x, c.d);
    EXPECT_TRUE(limited.limited());
    const Points probe = test::random_points(4000, 0.0, 1.0, 5);
    const Points a = displacements(raw, probe), b = displacements(limited, probe);
    ASSERT_GT(a.rowwise().norm().maxCoeff(), 1.01 * c.lift) << "the premise: the RBF overshoots";
    EXPECT_LE(b.rowwise().norm().maxCoeff(), c.lift * (1 + 1e-15));
    // Exact at the constraints as before (no prescription is larger than the limit) ...
    EXPECT_LE((displacements(limited, c.x) - c.d).rowwise().norm().maxCoeff(), 1e-12 * c.lift);
    // ... unchanged where the raw field stays within it, and never steeper (1-Lipschitz).
    for (Eigen::Index i = 0; i < probe.rows(); ++i)
    {
        if (a.row(i).norm() <= c.lift)
        {
            EXPECT_EQ(b.row(i), a.row(i)) << "probe " << i;
        }
        const Eigen::Index j = (i * 7919) % probe.rows();
        EXPECT_LE((b.row(i) - b.row(j)).norm(), (a.row(i) - a.row(j)).norm() * (1 + 1e-12) + 1e-15);
    }
}

TEST(CorrectedDeformation, a_limited_field_written_and_read_back_evaluates_alike)
{
    const LiftedBall c;
    CorrectedDeformation limited(std::make_unique<RbfDeformation>(), IdwSettings{}, true);
    limited.fit(c.x, c.d);
    const std::string bytes = write_field(limited);
    const std::unique_ptr<SpaceDeformation> restored = read_field(bytes);
    const Points probe = test::random_points(500, 0.0, 1.0, 9);
    EXPECT_EQ(displacements(*restored, probe), displacements(limited, probe));
    EXPECT_EQ(write_field(*restored), bytes);
}

} // namespace meshmorph
