// SPDX-License-Identifier: GPL-3.0-or-later
// Properties of DM-FFD: equals a reference pseudo-inverse, least squares / least norm,
// clamping bounds the blow-up of the paper's Fig. 8, handle basis.
#include <gtest/gtest.h>

#include <Eigen/QR>

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
