// SPDX-License-Identifier: GPL-3.0-or-later
// A coarse greedy RBF made exact by the IDW correction of its residual
// (src/meshmorph/deform/corrected_deformation.*).
#include <gtest/gtest.h>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/corrected_deformation.h"
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

} // namespace meshmorph
