// SPDX-License-Identifier: GPL-3.0-or-later
// A coarse greedy RBF made exact by the IDW correction of its residual
// (src/meshmorph/deform/corrected_deformation.*).
#include <gtest/gtest.h>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
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
    const log::CaptureScope capture;
    corrected.fit(x, d);
    EXPECT_EQ(corrected.report().method, "greedy-rbf+idw");
    const double max_d = test::max_norm(d);
    EXPECT_LE((displacements(corrected, x) - d).rowwise().norm().maxCoeff(), 1e-12 * max_d);
    // The designed path, as exact: a log line, not a warning.
    EXPECT_NE(capture.text().find("using the greedy RBF instead"), std::string::npos);
    EXPECT_EQ(capture.text().find("Warning"), std::string::npos) << capture.text();
}

TEST(CorrectedDeformation, a_direct_rbf_whose_ill_conditioning_shows_falls_back_to_greedy)
{
    // The residual threshold is set below what the direct fit reaches, so that its
    // ill-conditioning shows; morphMesh's direct RBF asks for the error instead of the
    // warning (ill_conditioning_is_error), and the correction takes the greedy RBF.
    const test::ClusteredHandles c;
    const Points& x = c.h;
    const Points& d = c.d;
    RbfSettings s;
    RbfDeformation probe(s);
    probe.fit(x, d);
    const double relative = probe.report().max_residual / probe.report().max_displacement;
    ASSERT_GT(relative, 0.0) << "the premise: round-off leaves a residual";
    ASSERT_GT(probe.report().condition_estimate, s.condition_warning) << "the premise";
    s.residual_warning = 0.5 * relative;
    s.ill_conditioning_is_error = true;
    CorrectedDeformation corrected(std::make_unique<RbfDeformation>(s));
    const log::CaptureScope capture;
    corrected.fit(x, d);
    EXPECT_EQ(corrected.report().method, "greedy-rbf+idw");
    const double max_d = test::max_norm(d);
    EXPECT_LE((displacements(corrected, x) - d).rowwise().norm().maxCoeff(), 1e-12 * max_d);
    EXPECT_NE(capture.text().find("condition estimate"), std::string::npos) << capture.text();
    EXPECT_EQ(capture.text().find("Warning"), std::string::npos) << capture.text();
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

TEST(CorrectedDeformation, at_its_handles_it_gives_what_its_evaluation_gives_there)
{
    // The fitted field takes the global part's values at its handles from the fit; a field
    // read back (what every -parallel rank evaluates) has no such values and sums at every
    // point. Both must agree bit for bit, at handles and other points queried together and
    // in any order, or -parallel would not equal serial: for a greedy global part, a direct
    // one, and a direct one with the limit.
    const Points x = test::sphere_points(2000, Vector3(0.5, 0.5, 0.5), 0.5);
    const Points d = test::smooth_field(x);
    GreedySettings coarse;
    coarse.tolerance = 0.05;
    std::vector<std::unique_ptr<CorrectedDeformation>> fields;
    fields.push_back(
        std::make_unique<CorrectedDeformation>(std::make_unique<GreedyRbfDeformation>(coarse)));
    fields.push_back(std::make_unique<CorrectedDeformation>(std::make_unique<RbfDeformation>()));
    fields.push_back(std::make_unique<CorrectedDeformation>(std::make_unique<RbfDeformation>(),
                                                            IdwSettings{}, true));
    const Points other = test::random_points(1500, -0.2, 1.2, 11);
    Points mixed(x.rows() + other.rows(), 3);
    for (Eigen::Index i = 0, a = 0, b = 0; i < mixed.rows(); ++i)
        mixed.row(i) =
            (i % 3 == 0 && a < x.rows()) || b == other.rows() ? x.row(a++) : other.row(b++);
    for (const std::unique_ptr<CorrectedDeformation>& corrected : fields)
    {
        corrected->fit(x, d);
        ASSERT_NE(corrected->global().values_at_handles(), nullptr) << "the premise: kept";
        const std::unique_ptr<SpaceDeformation> restored = read_field(write_field(*corrected));
        EXPECT_EQ(displacements(*corrected, mixed), displacements(*restored, mixed))
            << corrected->report().method;
        EXPECT_LE((displacements(*corrected, x) - d).rowwise().norm().maxCoeff(),
                  1e-14 * test::max_norm(d))
            << corrected->report().method;
    }
}

TEST(ExactPointIndex, finds_rows_by_exact_coordinates_and_no_row_for_shared_ones)
{
    // Grid coordinates (0.5, 1.25: many trailing zero bits) must spread over the table.
    Points p(1003, 3);
    for (Eigen::Index i = 0; i < 1000; ++i)
        p.row(i) << double(i % 10) * 0.5, double((i / 10) % 10) * 1.25, double(i / 100) * 0.25;
    p.row(1000) << 0.0, -0.0, 7.0;  // -0 is the same point as +0
    p.row(1001) << 0.0, 0.0, 7.0;   // ... so this one and row 1000 share a point
    p.row(1002) << 0.5, 1.25, 0.25; // row 111's point again
    const detail::ExactPointIndex index(p);
    EXPECT_EQ(index.find(1.5, 2.5, 0.75), 3 * 1 + 10 * 2 + 100 * 3);
    EXPECT_EQ(index.find(0.0, 0.0, 7.0), -1) << "two rows share it";
    EXPECT_EQ(index.find(0.5, 1.25, 0.25), -1) << "two rows share it";
    EXPECT_EQ(index.find(0.5, 1.25, 0.25 + 1e-16), -1) << "not a point of the index";
    EXPECT_EQ(index.find(0.25, 0.0, 0.0), -1) << "not a point of the index";
    const std::vector<Index> rows = index.find_rows(p.topRows(1000));
    for (Index i = 0; i < 1000; ++i)
    {
        if (i != 111)
        {
            EXPECT_EQ(rows[std::size_t(i)], i);
        }
    }
    EXPECT_TRUE(detail::ExactPointIndex().empty());
    EXPECT_EQ(detail::ExactPointIndex().find(0.0, 0.0, 0.0), -1);
}

} // namespace meshmorph
