// SPDX-License-Identifier: GPL-3.0-or-later
// Properties of the greedy RBF refinement: meets its tolerance with far fewer centres than
// constraints on a smooth field, and with every constraint as a centre equals the full fit
// (which checks the incremental factorisation).
#include <algorithm>
#include <memory>

#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/deform/corrected_deformation.h"
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
        s.spread = 0.0;     // the plain largest residuals ...
        s.jump_slope = 0.0; // ... of every constraint, until all are centres
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

namespace meshmorph
{

TEST(GreedyRbfDeformation, logs_each_round_and_the_rounds_grow_like_log_of_the_centres)
{
    const Points x = test::sphere_points(6000, Vector3(0.5, 0.5, 0.5), 0.5);
    const Points d = test::smooth_field(x);
    GreedySettings s;
    s.tolerance = 1e-9; // not reachable within the budget: every round runs
    s.rms_tolerance = 1e-9;
    s.max_centres = 1280;
    s.spread = 0.0; // full batches: the count grows by 1.5 a round
    GreedyRbfDeformation greedy(s);
    log::CaptureScope capture;
    greedy.fit(x, d);
    const std::string& text = capture.text();
    std::size_t lines = 0;
    for (std::size_t at = text.find("greedy RBF round"); at != std::string::npos;
         at = text.find("greedy RBF round", at + 1))
        ++lines;
    EXPECT_EQ(lines, greedy.history().size()) << text;
    EXPECT_NE(text.find("centres, max residual"), std::string::npos);
    // Each round adds half the centres: from 20 initial centres to 1280 takes
    // log(64) / log(1.5) = 10.3 rounds, plus the first (the initial set) and the last (the
    // budget): at most 13.
    EXPECT_LE(greedy.history().size(), 13u);
    EXPECT_EQ(greedy.report().num_centres, 1280);
}

namespace
{

//! Near-discontinuous data, like a tyre lifted off a fixed floor: n random points of the
//! fixed plane z = 0 and n points of a sphere lifted by `lift`, a hair above the plane.
struct BallOnFloor
{
    Points x, d;
    Index n_plane = 0;
    explicit BallOnFloor(Eigen::Index n, double lift = 0.05)
    {
        Points plane = test::random_points(n, 0.0, 1.0, 17);
        plane.col(2).setZero();
        const Points ball = test::sphere_points(n, Vector3(0.5, 0.5, 0.2001), 0.2);
        x.resize(plane.rows() + ball.rows(), 3);
        x << plane, ball;
        d = Points::Zero(x.rows(), 3);
        d.bottomRows(ball.rows()).col(2).setConstant(lift);
        n_plane = plane.rows();
    }
};

} // namespace

TEST(GreedyRbfDeformation, stops_at_the_best_round_when_more_centres_make_the_fit_worse)
{
    // Near-discontinuous data, like a tyre lifted off a fixed floor: a plane of fixed points
    // and, a hair above it, a lifted sphere. A global interpolant of this oscillates as
    // centres are added; the fit must keep its best round, never a worse one.
    const BallOnFloor data(3000);
    const Points& x = data.x;
    const Points& d = data.d;
    GreedySettings s;
    s.tolerance = 1e-6;
    s.rms_tolerance = 1e-6;
    s.max_centres = 3000;
    s.spread = 0.0; // the crowded batches of the largest residuals, every constraint fitted
    s.jump_slope = 0.0;
    GreedyRbfDeformation greedy(s);
    log::CaptureScope capture;
    greedy.fit(x, d);
    ASSERT_TRUE(greedy.stopped_growing()) << capture.text();
    EXPECT_NE(capture.text().find("keeping the"), std::string::npos);
    const std::vector<double>& rms = greedy.rms_history();
    ASSERT_FALSE(rms.empty());
    // The kept model is the best round, and the history ends with it.
    const double best = *std::min_element(rms.begin(), rms.end());
    EXPECT_EQ(rms.back(), best);
    EXPECT_NEAR(greedy.report().rms_residual, best, 1e-12 * 0.05);
    // The truncated factorisation is consistent: the handle basis interpolates the kept
    // centres (row of a centre = its unit vector).
    const std::vector<Index>& centres = greedy.centre_indices();
    EXPECT_EQ(Index(centres.size()), greedy.report().num_centres);
    Points at_centres(Eigen::Index(centres.size()), 3);
    for (std::size_t i = 0; i < centres.size(); ++i)
        at_centres.row(Eigen::Index(i)) = x.row(centres[i]);
    const Eigen::MatrixXd B = greedy.handle_basis(at_centres);
    for (std::size_t i = 0; i < centres.size(); ++i)
        for (Eigen::Index j = 0; j < B.cols(); ++j)
            ASSERT_NEAR(B(Eigen::Index(i), j), j == centres[i] ? 1.0 : 0.0, 1e-8)
                << "centre " << i << ", constraint " << j;
}

TEST(GreedyRbfDeformation, spread_batches_reach_the_tolerance_with_the_contact_left_out)
{
    // The data of the test above: a lifted sphere touching (a hair above) a fixed plane.
    // Crowded batches stop at the best round far from the tolerance; spread batches, with
    // the constraints next to the contact left to the local correction, reach it.
    const double lift = 0.05;
    const BallOnFloor data(3000, lift);
    const Points& x = data.x;
    const Points& d = data.d;
    const Index n_plane = data.n_plane;
    GreedySettings s;
    s.max_centres = 3000;
    s.spread = 0.0;
    s.jump_slope = 0.0;
    GreedyRbfDeformation crowded(s);
    crowded.fit(x, d);
    EXPECT_FALSE(crowded.converged());
    EXPECT_EQ(crowded.jump_constraints(), 0);

    s.spread = 1.0;
    s.jump_slope = 1.0;
    GreedyRbfDeformation spread(s);
    log::CaptureScope capture;
    spread.fit(x, d);
    EXPECT_TRUE(spread.converged()) << capture.text();
    EXPECT_FALSE(spread.stopped_growing());
    EXPECT_NE(capture.text().find("left to the local correction"), std::string::npos);
    // The jumps are the points around the contact and only those: a plane point and a
    // sphere point whose values differ by the lift closer than the lift (slope 1) lie
    // within ~sqrt(2 r lift) = 0.14 of the contact, horizontally.
    Points got(x.rows(), 3);
    spread.evaluate(x, got);
    Index jumps = 0;
    for (Eigen::Index i = 0; i < x.rows(); ++i)
    {
        const double r = std::hypot(x(i, 0) - 0.5, x(i, 1) - 0.5);
        const double z = x(i, 2);
        // Points beyond the band's reach are fitted to the tolerance.
        if (r > 0.2 && !(i >= n_plane && z < 0.2))
        {
            EXPECT_LE((got.row(i) - d.row(i)).norm(), 1e-2 * lift * (1 + 1e-9)) << "point " << i;
        }
        if (r < 0.02 && (i < n_plane || z < 0.01))
            ++jumps; // certainly on the jump: within the contact's neighbourhood
    }
    EXPECT_GT(jumps, 0);
    EXPECT_GE(spread.jump_constraints(), jumps);
    EXPECT_LT(spread.jump_constraints(), x.rows() / 10);
    // Each kept centre is interpolated exactly (the polynomial's unisolvent points may lie on
    // a jump; no other centre does).
    const std::vector<char>* left_out = spread.handles_left_out();
    ASSERT_NE(left_out, nullptr);
    ASSERT_EQ(Eigen::Index(left_out->size()), x.rows());
    EXPECT_EQ(std::count(left_out->begin(), left_out->end(), 1), spread.jump_constraints());
    for (Index c : spread.centre_indices())
        EXPECT_NEAR((got.row(c) - d.row(c)).norm(), 0.0, 1e-9 * lift);
    // The correction's tree expands clusters of the others from nearer (IdwTree, quiet
    // nodes): the corrected field is still exact at every constraint.
    CorrectedDeformation corrected(std::make_unique<GreedyRbfDeformation>(s));
    corrected.fit(x, d);
    Points exact(x.rows(), 3);
    corrected.evaluate(x, exact);
    EXPECT_LE((exact - d).cwiseAbs().maxCoeff(), 1e-12 * lift);
}

TEST(GreedyRbfDeformation, fits_a_small_motion_of_a_contact_the_same_way_at_any_amplitude)
{
    // The lifted ball on the floor at two small lifts a factor 4 apart (powers of two, so
    // that scaling the data is exact in floating point). The jump band's floor (jump_width
    // of the ball's extent, 0.017) is wider than either lift over jumpSlope 2: the same
    // constraints are left out, the same centres chosen, and the field is 4 times the
    // other. A band bound to the lift alone leaves out fewer constraints the smaller the
    // lift, so the two fits differ.
    const double small = 1.0 / 256.0, large = 1.0 / 64.0;
    const BallOnFloor a(2000, small), b(2000, large);
    GreedySettings s;
    const auto fitted = [&](const BallOnFloor& data)
    {
        auto greedy = std::make_unique<GreedyRbfDeformation>(s);
        greedy->fit(data.x, data.d);
        return greedy;
    };
    const auto fa = fitted(a), fb = fitted(b);
    ASSERT_TRUE(fa->converged());
    ASSERT_TRUE(fb->converged());
    EXPECT_GT(fa->jump_constraints(), 0);
    EXPECT_EQ(fa->jump_constraints(), fb->jump_constraints());
    EXPECT_EQ(fa->centre_indices(), fb->centre_indices());
    const Points probe = test::random_points(500, 0.0, 1.0, 29);
    const Points va = displacements(*fa, probe), vb = displacements(*fb, probe);
    EXPECT_LE((4.0 * va - vb).cwiseAbs().maxCoeff(), 1e-12 * large);

    s.jump_width = 0.0; // the band of the slope alone: lift / 2
    const auto ga = fitted(a), gb = fitted(b);
    EXPECT_LT(ga->jump_constraints(), gb->jump_constraints());
    EXPECT_LT(gb->jump_constraints(), fb->jump_constraints());
}

//! values_at_handles() is the field at every constraint bit for bit, as evaluate() gives it
//! (what CorrectedDeformation subtracts from the prescriptions instead of evaluating again).
void expect_values_at_handles_as_evaluated(const GreedyRbfDeformation& greedy, const Points& x)
{
    const Points* kept = greedy.values_at_handles();
    ASSERT_NE(kept, nullptr);
    ASSERT_EQ(kept->rows(), x.rows());
    Points got(x.rows(), 3);
    greedy.evaluate(x, got);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        for (int k = 0; k < 3; ++k)
            ASSERT_EQ((*kept)(i, k), got(i, k)) << "constraint " << i << ", component " << k;
}

TEST(GreedyRbfDeformation, keeps_its_values_at_the_constraints_with_the_bits_of_an_evaluation)
{
    // A converged fit whose constraints include a merged duplicate (the same point a
    // hair away, with the same displacement): its value is evaluated, the others are the
    // last round's.
    Points x = test::sphere_points(2000, Vector3(0.5, 0.5, 0.5), 0.5);
    x.conservativeResize(x.rows() + 1, 3);
    x.row(x.rows() - 1) = x.row(7) + Eigen::RowVector3d(1e-15, 0.0, 0.0);
    const Points d = test::smooth_field(x);
    GreedyRbfDeformation smooth{GreedySettings{}};
    EXPECT_EQ(smooth.values_at_handles(), nullptr); // not fitted yet
    smooth.fit(x, d);
    ASSERT_TRUE(smooth.converged());
    ASSERT_EQ(smooth.report().num_merged_duplicates, 1);
    expect_values_at_handles_as_evaluated(smooth, x);

    // A refinement truncated to its best round: the last round's values are not the kept
    // model's, so every constraint is evaluated.
    const BallOnFloor data(3000);
    GreedySettings s;
    s.tolerance = 1e-6;
    s.rms_tolerance = 1e-6;
    s.max_centres = 3000;
    s.spread = 0.0;
    s.jump_slope = 0.0;
    GreedyRbfDeformation truncated(s);
    truncated.fit(data.x, data.d);
    ASSERT_TRUE(truncated.stopped_growing());
    expect_values_at_handles_as_evaluated(truncated, data.x);
}

TEST(GreedyRbfDeformation, rejects_negative_spread_jump_slope_or_jump_width)
{
    GreedySettings s;
    s.spread = -1.0;
    EXPECT_THROW(GreedyRbfDeformation{s}, InvalidInput);
    s.spread = 0.0;
    s.jump_slope = -0.5;
    EXPECT_THROW(GreedyRbfDeformation{s}, InvalidInput);
    s.jump_slope = 2.0;
    s.jump_width = -0.01;
    EXPECT_THROW(GreedyRbfDeformation{s}, InvalidInput);
}

TEST(GreedyRbfDeformation, spread_refinement_gives_the_same_field_on_one_thread_and_on_two)
{
#ifndef _OPENMP
    GTEST_SKIP() << "built without OpenMP: one thread only";
#else
    // Hundreds of centres: large enough for a threaded matrix product to split its work
    // by the thread count. Centres are chosen from residuals that the conditioning amplifies,
    // so the last bits of the factor must not depend on the threads.
    const BallOnFloor data(4000);
    const Points& x = data.x;
    const Points& d = data.d;
    const Points probe = test::random_points(3000, 0.0, 1.0, 23);
    GreedySettings s;
    s.tolerance = 1e-3;
    s.rms_tolerance = 1e-3;
    const int threads = omp_get_max_threads();
    std::vector<Points> fields;
    std::vector<std::vector<Index>> centres;
    for (int t : {1, 2})
    {
        omp_set_num_threads(t);
        GreedyRbfDeformation greedy(s);
        greedy.fit(x, d);
        fields.push_back(displacements(greedy, probe));
        centres.push_back(greedy.centre_indices());
    }
    omp_set_num_threads(threads);
    EXPECT_GT(centres[0].size(), 300u) << "the premise: products large enough to be threaded";
    EXPECT_EQ(centres[0], centres[1]);
    EXPECT_EQ(fields[0], fields[1]);
#endif
}

} // namespace meshmorph
