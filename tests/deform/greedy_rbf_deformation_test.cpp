// SPDX-License-Identifier: GPL-3.0-or-later
// Properties of the greedy RBF refinement: meets its tolerance with far fewer centres than
// constraints on a smooth field, and with every constraint as a centre equals the full fit
// (which checks the incremental factorisation).
#include <gtest/gtest.h>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"

namespace meshmorph
{

TEST(GreedyRbfDeformation, meets_tolerance_with_few_centres_on_a_smooth_field)
{
    // A morphing-like set-up: constraints on a closed surface with a smooth field.
    const Points x = test::sphere_points(4000, Vector3(0.5, 0.5, 0.5), 0.5);
    const Points d = test::smooth_field(x);
    GreedySettings s;
    s.tolerance = 1e-2;
    s.rms_tolerance = 1e-3;
    GreedyRbfDeformation greedy(s);
    greedy.fit(x, d);
    ASSERT_TRUE(greedy.converged());
    const double max_d = test::max_norm(d);
    // Check the residual independently of the report.
    const Points got = displacements(greedy, x);
    const Eigen::VectorXd err = (got - d).rowwise().norm();
    EXPECT_LE(err.maxCoeff(), 1e-2 * max_d);
    EXPECT_LE(std::sqrt(err.squaredNorm() / double(err.size())), 1e-3 * max_d);
    EXPECT_NEAR(greedy.report().max_residual, err.maxCoeff(), 1e-15);
    EXPECT_LT(greedy.report().num_centres, 400); // < 10% of the 4000 constraints
    EXPECT_EQ(Index(greedy.centre_indices().size()), greedy.report().num_centres);
    // Centres are interpolated exactly.
    for (Index c : greedy.centre_indices())
        EXPECT_LE((got.row(c) - d.row(c)).norm(), 1e-10 * max_d);
}

TEST(GreedyRbfDeformation, with_all_constraints_as_centres_equals_the_full_fit)
{
    const Points x = test::random_points(400, 0.0, 1.0, 41);
    const Points d = test::smooth_field(x);
    const Points probe = test::random_points(200, -0.2, 1.2, 43);
    // Well-conditioned kernels only: a flat Gaussian would make both fits differ by round-off
    // amplified by a condition number of ~1e15.
    for (RbfKernel k : {RbfKernel::triharmonic, RbfKernel::biharmonic, RbfKernel::polyharmonic,
                        RbfKernel::wendland_c2})
    {
        GreedySettings s;
        s.rbf.kernel = k;
        s.rbf.polyharmonic_order = 4; // r^5 with 10 quadratic terms
        s.rbf.support_radius = 0.6;
        s.tolerance = 0.0;
        s.rms_tolerance = 0.0;
        s.max_centres = 400;
        GreedyRbfDeformation greedy(s);
        greedy.fit(x, d);
        EXPECT_EQ(greedy.report().num_centres, 400) << to_string(k);
        EXPECT_TRUE(greedy.converged());
        RbfDeformation full(s.rbf);
        full.fit(x, d);
        EXPECT_LE((displacements(greedy, probe) - displacements(full, probe)).cwiseAbs().maxCoeff(),
                  1e-8 * test::max_norm(d))
            << to_string(k);
    }
}

TEST(GreedyRbfDeformation, reproduces_affine_motion_with_the_initial_centres)
{
    const Points x = test::random_points(500, 0.0, 2.0, 3);
    const Eigen::Matrix3d L = Eigen::AngleAxisd(0.2, Vector3::UnitZ()).matrix() * 1.3;
    const Points d = test::affine_displacements(x, L, Vector3(1, 2, 3));
    GreedyRbfDeformation greedy;
    greedy.fit(x, d);
    EXPECT_TRUE(greedy.converged());
    EXPECT_EQ(greedy.report().iterations, 0);
    EXPECT_LE(greedy.report().max_residual, 1e-10 * test::max_norm(d));
}

TEST(GreedyRbfDeformation, budget_stops_refinement_and_reports_the_residual)
{
    const Points x = test::random_points(1000, 0.0, 1.0, 5);
    const Points d = test::smooth_field(x);
    GreedySettings s;
    s.tolerance = 1e-12;
    s.rms_tolerance = 1e-12;
    s.max_centres = 30;
    GreedyRbfDeformation greedy(s);
    greedy.fit(x, d);
    EXPECT_FALSE(greedy.converged());
    EXPECT_EQ(greedy.report().num_centres, 30);
    EXPECT_GT(greedy.report().max_residual, 0.0);
    // The error decreases over the iterations (not necessarily monotonically per step).
    ASSERT_GE(greedy.history().size(), 2u);
    EXPECT_LT(greedy.history().back(), greedy.history().front());
}

TEST(GreedyRbfDeformation, rejects_bad_input)
{
    GreedySettings s;
    s.tolerance = -1.0;
    EXPECT_THROW(GreedyRbfDeformation{s}, InvalidInput);
    s = GreedySettings{};
    s.max_centres = 0;
    EXPECT_THROW(GreedyRbfDeformation{s}, InvalidInput);
    GreedyRbfDeformation greedy;
    EXPECT_THROW(greedy.fit(Points(0, 3), Points(0, 3)), InvalidInput);
    EXPECT_THROW(greedy.fit(test::random_points(4), Points::Zero(3, 3)), InvalidInput);
}

} // namespace meshmorph
