// SPDX-License-Identifier: GPL-3.0-or-later
// Properties of DM-FFD: equals a reference pseudo-inverse, least squares / least norm,
// clamping bounds the blow-up of the paper's Fig. 8, handle basis.
#include <gtest/gtest.h>

#include <Eigen/QR>

#include <cmath>
#include <utility>
#include <vector>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/dmffd_deformation.h"

namespace meshmorph
{
namespace
{
DmffdSettings unit_box_settings(int n, double clamping)
{
    DmffdSettings s;
    s.lattice.control_points = {n, n, n};
    s.lattice.box = FfdBox{};
    s.clamping = clamping;
    return s;
}
} // namespace

TEST(DmffdDeformation, equals_reference_pseudo_inverse)
{
    // Under-determined (30 handles, 125 controls) and over-determined (400 handles).
    for (Eigen::Index m : {30, 400})
    {
        const Points h = test::random_points(m, 0.05, 0.95, unsigned(m));
        const Points d = test::smooth_field(h);
        DmffdDeformation dm(unit_box_settings(5, 1e-12));
        dm.fit(h, d);
        const Eigen::MatrixXd Phi = dm.ffd().basis_matrix(h);
        const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(Phi);
        const Eigen::MatrixXd C = cod.solve(Eigen::MatrixXd(d));
        EXPECT_LE((Eigen::MatrixXd(dm.ffd().control_displacements()) - C).cwiseAbs().maxCoeff(),
                  1e-9)
            << m;
        if (m < 125)
        {
            EXPECT_LE(dm.report().max_residual, 1e-12); // least norm: constraints met
        }
    }
}

TEST(DmffdDeformation, recovers_an_ffd_field_in_the_least_squares_case)
{
    const FfdLattice lattice(FfdBox{}, {5, 5, 5});
    FfdDeformation truth(lattice);
    truth.set_control_displacements(test::smooth_field(lattice.control_points()));
    const Points h = test::random_points(2000, 0.0, 1.0, 3);
    DmffdDeformation dm(unit_box_settings(5, 1e-8));
    dm.fit(h, displacements(truth, h));
    EXPECT_EQ(dm.report().rank, 125);
    EXPECT_LE(dm.report().max_residual, 1e-12);
    const Points x = test::random_points(300, 0.0, 1.0, 8);
    EXPECT_LE((displacements(dm, x) - displacements(truth, x)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(DmffdDeformation, clamping_bounds_the_blow_up_of_fig8)
{
    // Paper Fig. 8: 5^3 lattice, handles on a sphere; tiny clamping lets poorly determined
    // control points (lattice corners) explode, 1e-2 keeps the deformation tame.
    const Points h = test::sphere_points(400, Vector3(0.5, 0.5, 0.5), 0.3);
    Points d(h.rows(), 3);
    for (Eigen::Index i = 0; i < h.rows(); ++i)
        d.row(i) = 0.05 * (h.row(i) - Eigen::RowVector3d(0.5, 0.5, 0.5)).normalized() *
                   std::sin(6.0 * h(i, 0));
    const Points x = test::random_points(3000);
    double max_d[2];
    int k = 0;
    for (double clamping : {1e-10, 1e-2})
    {
        DmffdDeformation dm(unit_box_settings(5, clamping));
        dm.fit(h, d);
        max_d[k++] = test::max_norm(displacements(dm, x));
    }
    EXPECT_GT(max_d[0], 10.0 * max_d[1]) << max_d[0] << " vs " << max_d[1];
    EXPECT_LE(max_d[1], 5.0 * test::max_norm(d));
}

TEST(DmffdDeformation, handle_basis_reproduces_a_fresh_fit)
{
    const Points h = test::random_points(80, 0.1, 0.9, 4);
    const Points x = test::random_points(200, 0.0, 1.0, 6);
    DmffdDeformation dm(unit_box_settings(6, 1e-2));
    dm.fit(h, test::smooth_field(h));
    const Eigen::MatrixXd B = dm.handle_basis(x);
    const Points H = test::smooth_field(h * 0.7) * 2.0;
    DmffdDeformation fresh(unit_box_settings(6, 1e-2));
    fresh.fit(h, H);
    const Points bh = B * H;
    EXPECT_LE((bh - displacements(fresh, x)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(DmffdDeformation, rejects_bad_input)
{
    EXPECT_THROW(DmffdDeformation{unit_box_settings(3, 1e-2)}, InvalidInput);
    EXPECT_THROW(DmffdDeformation{unit_box_settings(5, -1.0)}, InvalidInput);
    DmffdDeformation dm(unit_box_settings(5, 1e-2));
    EXPECT_THROW(dm.fit(Points(0, 3), Points(0, 3)), InvalidInput);
    EXPECT_THROW(dm.fit(test::random_points(5), Points::Zero(4, 3)), InvalidInput);
    Points bad = test::random_points(5);
    bad(2, 2) = std::numeric_limits<double>::infinity();
    EXPECT_THROW(dm.fit(bad, Points::Zero(5, 3)), InvalidInput);
}

} // namespace meshmorph

namespace meshmorph
{
TEST(DmffdDeformation, invariant_under_scaling_of_the_problem)
{
    const Points h = test::random_points(200, 0.0, 1.0, 17);
    const Points d = test::smooth_field(h);
    const Points x = test::random_points(100, 0.0, 1.0, 19);
    DmffdSettings s;
    s.lattice.control_points = {5, 6, 5};
    DmffdDeformation ref(s);
    ref.fit(h, d);
    const Points expected = displacements(ref, x);
    for (double scale : {1e-6, 1e6})
    {
        DmffdDeformation dm(s);
        dm.fit(h * scale, d * scale);
        EXPECT_EQ(dm.report().rank, ref.report().rank);
        const Points got = displacements(dm, x * scale) / scale;
        EXPECT_LE((got - expected).cwiseAbs().maxCoeff(), 1e-10 * test::max_norm(d)) << scale;
    }
}
} // namespace meshmorph

namespace meshmorph
{
namespace
{
//! Paper Fig. 12 set-up, small: an n x n grid on the plane z = 0 over [0,1]^2, target the
//! plane with a sharp Gaussian bump of height 0.2 and width sigma at `centre`.
struct BumpProblem
{
    Points x, d;
    Vector3 centre{0.62, 0.37, 0.0};
    double sigma = 0.06;
    explicit BumpProblem(int n)
    {
        x.resize(Eigen::Index(n) * n, 3);
        d = Points::Zero(x.rows(), 3);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
            {
                const Eigen::Index p = i + Eigen::Index(n) * j;
                x.row(p) = Eigen::RowVector3d(double(i) / (n - 1), double(j) / (n - 1), 0.0);
                const double r2 = (x.row(p).transpose() - centre).squaredNorm();
                d(p, 2) = 0.2 * std::exp(-r2 / (2.0 * sigma * sigma));
            }
    }
};

DmffdRefinement plane_refinement(double tolerance, Index budget)
{
    DmffdRefinement r;
    r.tolerance = tolerance;
    r.max_control_points = budget;
    r.axes = {true, true, false}; // the paper's x and y only: z is flat
    return r;
}
} // namespace

TEST(DmffdDeformation, control_plane_refinement_resolves_a_local_bump)
{
    const BumpProblem bump(21);
    DmffdSettings s;
    s.lattice.control_points = {4, 4, 4};
    DmffdDeformation dm(s);
    // 1% of the bump height, within the paper's budget of as many DoF as constraints: the
    // plane cannot tell the 4 z-planes apart (rank nx ny), so nx ny <= m, i.e. 4 m control
    // points. The coarse 4^3 lattice misses the bump almost entirely.
    const double tolerance = 1e-2;
    dm.fit_refined(bump.x, bump.d, plane_refinement(tolerance, 4 * bump.x.rows()));
    const std::vector<DmffdRefinementStep>& history = dm.refinement_history();
    const double max_d = dm.report().max_displacement;
    ASSERT_GE(history.size(), 3u);
    EXPECT_GT(history.front().max_residual, 0.5 * max_d);
    EXPECT_TRUE(dm.refinement_converged());
    EXPECT_LE(dm.report().max_residual, tolerance * max_d);
    EXPECT_EQ(history.back().max_residual, dm.report().max_residual);
    EXPECT_EQ(Index(history.size()) - 1, dm.report().iterations);
    for (std::size_t k = 1; k < history.size(); ++k)
        EXPECT_GT(history[k].control_points, history[k - 1].control_points);

    // The planes went to the feature: its knot spans are at least 2 halvings finer than the
    // spans far from it, in x and in y; z was not refined.
    const FfdLattice& lattice = dm.ffd().lattice();
    EXPECT_EQ(lattice.counts()[2], 4);
    const Vector3 near = lattice.local_coordinates(bump.centre);
    const Vector3 far = lattice.local_coordinates(Vector3(0.05, 0.95, 0.0));
    for (int a = 0; a < 2; ++a)
    {
        const std::pair<double, double> fine = lattice.knot_span(a, near[a]);
        const std::pair<double, double> coarse = lattice.knot_span(a, far[a]);
        EXPECT_LE(4.0 * (fine.second - fine.first), coarse.second - coarse.first) << a;
    }
}

TEST(DmffdDeformation, control_plane_refinement_never_increases_the_rms_residual)
{
    // Knot insertion nests the spline spaces (the old lattice's functions are in the new
    // space), so the least-squares residual cannot grow when no direction is clamped away:
    // clamping 1e-10 keeps all but the exactly-zero directions (control points with no handle
    // in their support). Slack 1e-9 relative: round-off of the SVD solves.
    const BumpProblem bump(21);
    DmffdSettings s;
    s.lattice.control_points = {4, 4, 4};
    s.clamping = 1e-10;
    DmffdDeformation dm(s);
    dm.fit_refined(bump.x, bump.d, plane_refinement(1e-4, 900));
    const std::vector<DmffdRefinementStep>& history = dm.refinement_history();
    ASSERT_GE(history.size(), 4u);
    for (std::size_t k = 1; k < history.size(); ++k)
        EXPECT_LE(history[k].rms_residual, history[k - 1].rms_residual * (1.0 + 1e-9)) << k;
    EXPECT_LT(history.back().rms_residual, 0.1 * history.front().rms_residual);
}

TEST(DmffdDeformation, refinement_rejects_bad_settings)
{
    const BumpProblem bump(6);
    DmffdDeformation dm;
    DmffdRefinement r;
    r.axes = {false, false, false};
    EXPECT_THROW(dm.fit_refined(bump.x, bump.d, r), InvalidInput);
    r = DmffdRefinement{};
    r.tolerance = -1.0;
    EXPECT_THROW(dm.fit_refined(bump.x, bump.d, r), InvalidInput);
    r = DmffdRefinement{};
    r.grading = 1.5;
    EXPECT_THROW(dm.fit_refined(bump.x, bump.d, r), InvalidInput);
}
} // namespace meshmorph
