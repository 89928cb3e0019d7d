// SPDX-License-Identifier: GPL-3.0-or-later
// Properties of the B-spline lattice and classic FFD: linear precision (affine motions are
// reproduced everywhere in the box, boundary included), outside policies, Newton local
// coordinates on parallelepiped lattices, bad input; non-uniform knots (Cox-de Boor) and knot
// insertion keep these properties.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <utility>
#include <vector>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/ffd_deformation.h"

namespace meshmorph
{
namespace
{
FfdBox skewed_box()
{
    FfdBox box;
    box.origin = Vector3(-0.2, 0.1, 0.3);
    box.axes.col(0) = Vector3(1.2, 0.2, 0.0);
    box.axes.col(1) = Vector3(-0.3, 0.9, 0.1);
    box.axes.col(2) = Vector3(0.1, -0.2, 1.1);
    return box;
}

//! Points inside the box, including its 8 corners and face centres.
Points points_in(const FfdBox& box, Eigen::Index n)
{
    const Points u = test::random_points(n, 0.0, 1.0, 21);
    Points x(n + 8 + 6, 3);
    for (Eigen::Index i = 0; i < n; ++i)
        x.row(i) = (box.origin + box.axes * u.row(i).transpose()).transpose();
    for (int c = 0; c < 8; ++c)
        x.row(n + c) =
            (box.origin + box.axes * Vector3(c & 1, (c >> 1) & 1, (c >> 2) & 1)).transpose();
    for (int f = 0; f < 6; ++f)
    {
        Vector3 u0(0.5, 0.5, 0.5);
        u0[f / 2] = f % 2;
        x.row(n + 8 + f) = (box.origin + box.axes * u0).transpose();
    }
    return x;
}
} // namespace

TEST(FfdLattice, rejects_fewer_than_four_control_points_per_axis)
{
    EXPECT_THROW(FfdLattice(FfdBox{}, {3, 4, 4}), InvalidInput);
    EXPECT_THROW(FfdLattice::bounding(test::random_points(5), {4, 4, 2}, 0.0), InvalidInput);
    FfdBox flat;
    flat.axes.col(2).setZero();
    EXPECT_THROW(FfdLattice(flat, {4, 4, 4}), InvalidInput);
}

TEST(FfdLattice, basis_is_a_partition_of_unity_on_the_closed_box)
{
    const FfdLattice lattice(skewed_box(), {4, 6, 5});
    const Points x = points_in(lattice.box(), 200);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
    {
        Index idx[64];
        double w[64];
        ASSERT_EQ(lattice.basis(x.row(i).transpose(), FfdOutside::zero, idx, w), 64) << i;
        double sum = 0.0;
        Vector3 reproduced = Vector3::Zero();
        for (int k = 0; k < 64; ++k)
        {
            sum += w[k];
            reproduced += w[k] * lattice.control_points().row(idx[k]).transpose();
        }
        EXPECT_NEAR(sum, 1.0, 1e-14);
        // Linear precision: the undeformed lattice maps every point to itself (Eq. 1).
        EXPECT_LE((reproduced - x.row(i).transpose()).norm(), 1e-13);
    }
}

TEST(FfdLattice, newton_local_coordinates_invert_a_parallelepiped)
{
    const FfdLattice lattice(skewed_box(), {5, 5, 6});
    ASSERT_FALSE(lattice.is_axis_aligned());
    const Vector3 u(0.3, 0.8, 0.55);
    const Vector3 x = lattice.box().origin + lattice.box().axes * u;
    const Vector3 t = lattice.local_coordinates(x);
    EXPECT_LE((t - u.cwiseProduct(Vector3(2, 2, 3))).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(FfdDeformation, reproduces_affine_control_motion_everywhere_including_the_boundary)
{
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.5, Vector3(1, 1, 0).normalized()).matrix();
    const Eigen::Matrix3d maps[] = {Eigen::Matrix3d::Identity(), rot,
                                    Vector3(1.3, 0.6, 1.1).asDiagonal().toDenseMatrix()};
    const Vector3 t(0.3, -0.1, 0.2);
    for (const FfdBox& box : {FfdBox{}, skewed_box()})
    {
        const FfdLattice lattice(box, {4, 5, 7});
        const Points x = points_in(box, 300);
        for (const Eigen::Matrix3d& L : maps)
        {
            FfdDeformation ffd(lattice);
            ffd.fit(lattice.control_points(),
                    test::affine_displacements(lattice.control_points(), L, t));
            EXPECT_LE(
                (displacements(ffd, x) - test::affine_displacements(x, L, t)).cwiseAbs().maxCoeff(),
                1e-12);
        }
    }
}

TEST(FfdDeformation, bounding_lattice_moves_points_on_the_bounds)
{
    // PyGeM issue 272: points on the lattice boundary must follow a translation fully.
    const Points x = points_in(FfdBox{}, 50);
    for (double margin : {0.0, 0.05})
    {
        const FfdLattice lattice = FfdLattice::bounding(x, {4, 4, 4}, margin);
        FfdDeformation ffd(lattice);
        ffd.set_control_displacements(Points::Constant(lattice.size(), 3, 0.1));
        EXPECT_LE((displacements(ffd, x).array() - 0.1).abs().maxCoeff(), 1e-14) << margin;
    }
}

TEST(FfdDeformation, outside_points_follow_the_documented_policy)
{
    const FfdLattice lattice(FfdBox{}, {5, 5, 5});
    Points c = test::smooth_field(lattice.control_points());
    Points x(3, 3);
    x << 1.5, 0.5, 0.5, -0.2, 0.3, 1.4, 0.5, 0.5, 0.5;
    Points nearest(3, 3);
    nearest << 1.0, 0.5, 0.5, 0.0, 0.3, 1.0, 0.5, 0.5, 0.5;
    FfdDeformation zero(lattice, FfdOutside::zero);
    zero.set_control_displacements(c);
    const Points dz = displacements(zero, x);
    EXPECT_EQ(dz.row(0).norm(), 0.0);
    EXPECT_EQ(dz.row(1).norm(), 0.0);
    EXPECT_GT(dz.row(2).norm(), 0.0);
    FfdDeformation clamp(lattice, FfdOutside::clamp);
    clamp.set_control_displacements(c);
    EXPECT_LE((displacements(clamp, x) - displacements(clamp, nearest)).cwiseAbs().maxCoeff(),
              1e-15);
}

TEST(FfdDeformation, rejects_bad_input)
{
    const FfdLattice lattice(FfdBox{}, {4, 4, 4});
    FfdDeformation ffd(lattice);
    Points out(2, 3);
    EXPECT_THROW(ffd.evaluate(Points::Zero(2, 3), out), InvalidInput); // not fitted
    EXPECT_THROW(ffd.set_control_displacements(Points::Zero(63, 3)), InvalidInput);
    EXPECT_THROW(ffd.fit(test::random_points(64), Points::Zero(64, 3)), InvalidInput);
    Points bad = Points::Zero(64, 3);
    bad(5, 0) = std::nan("");
    EXPECT_THROW(ffd.set_control_displacements(bad), InvalidInput);
    ffd.set_control_displacements(Points::Zero(64, 3));
    Points nan_point = Points::Zero(2, 3);
    nan_point(1, 2) = std::nan("");
    EXPECT_THROW(ffd.evaluate(nan_point, out), InvalidInput);
    EXPECT_THROW(ffd.evaluate(Points::Zero(3, 3), out), InvalidInput); // 3 points, 2 rows out
    EXPECT_EQ(ffd_outside_from_string("clamp"), FfdOutside::clamp);
    EXPECT_THROW(ffd_outside_from_string("wrap"), InvalidInput);
}

TEST(FfdDeformation, evaluation_is_independent_of_thread_count)
{
    const FfdLattice lattice(skewed_box(), {6, 6, 6});
    FfdDeformation ffd(lattice, FfdOutside::clamp);
    ffd.set_control_displacements(test::smooth_field(lattice.control_points()));
    const Points x = test::random_points(4000, -0.5, 1.5, 5);
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const Points one = displacements(ffd, x);
    omp_set_num_threads(2);
    const Points two = displacements(ffd, x);
    omp_set_num_threads(saved);
    EXPECT_TRUE((one.array() == two.array()).all());
}

namespace
{
//! Insert knots at uneven places on all three axes (several in one span, clustered).
FfdLattice refined_lattice(const FfdBox& box)
{
    FfdLattice lattice(box, {4, 5, 4});
    const double inserts[][2] = {{0, 0.5}, {0, 0.25}, {0, 0.3},  {1, 1.7}, {1, 0.2},
                                 {2, 0.9}, {0, 0.26}, {2, 0.95}, {1, 1.71}};
    for (const auto& k : inserts)
        lattice = lattice.with_inserted_knot(int(k[0]), k[1]);
    return lattice;
}
} // namespace

TEST(FfdLattice, cox_de_boor_equals_the_uniform_closed_form)
{
    // The non-uniform evaluation on the uniform knots j - 3 must give the closed form.
    const int n = 7;
    std::vector<double> knots(n + 4);
    for (std::size_t j = 0; j < knots.size(); ++j)
        knots[j] = double(j) - 3.0;
    for (double t = 0.0; t <= n - 3; t += 0.0625)
    {
        int f0 = 0, f1 = 0;
        double w0[4], w1[4], d0[4], d1[4];
        detail::cubic_bspline(t, n, f0, w0, d0);
        detail::cubic_bspline(t, knots, f1, w1, d1);
        EXPECT_EQ(f0, f1) << t;
        for (int r = 0; r < 4; ++r)
        {
            EXPECT_NEAR(w0[r], w1[r], 1e-15) << t;
            EXPECT_NEAR(d0[r], d1[r], 1e-14) << t;
        }
    }
}

TEST(FfdLattice, non_uniform_basis_is_a_partition_of_unity_with_consistent_derivatives)
{
    const std::vector<double> knots = {-1.0, -0.6, -0.1, 0.0, 0.05, 0.07, 0.4, 1.0, 1.3, 2.0, 2.2};
    for (double t = 0.0; t <= 1.0; t += 1.0 / 64)
    {
        int first = 0;
        double w[4], dw[4];
        detail::cubic_bspline(t, knots, first, w, dw);
        EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, 1e-14) << t;
        EXPECT_NEAR(dw[0] + dw[1] + dw[2] + dw[3], 0.0, 1e-12) << t;
        for (int r = 0; r < 4; ++r)
            EXPECT_GE(w[r], 0.0) << t;
        // Central differences inside the span (h small against the 0.02-wide span).
        const double h = 1e-6;
        if (t - h < 0.0 || t + h > 1.0)
            continue;
        int fp = 0, fm = 0;
        double wp[4], wm[4];
        detail::cubic_bspline(t + h, knots, fp, wp, nullptr);
        detail::cubic_bspline(t - h, knots, fm, wm, nullptr);
        if (fp != first || fm != first)
            continue; // straddles a knot
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(dw[r], (wp[r] - wm[r]) / (2.0 * h), 1e-6 * (1.0 + std::abs(dw[r]))) << t;
    }
}

TEST(FfdLattice, knot_insertion_keeps_identity_and_affine_reproduction)
{
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.5, Vector3(1, 1, 0).normalized()).matrix();
    const Vector3 t(0.3, -0.1, 0.2);
    for (const FfdBox& box : {FfdBox{}, skewed_box()})
    {
        const FfdLattice lattice = refined_lattice(box);
        ASSERT_EQ(lattice.counts()[0], 8);
        ASSERT_EQ(lattice.counts()[1], 8);
        ASSERT_EQ(lattice.counts()[2], 6);
        EXPECT_FALSE(lattice.is_uniform(0) || lattice.is_uniform(1) || lattice.is_uniform(2));
        const Points x = points_in(box, 300);
        // Identity: the undeformed lattice maps every point to itself (linear precision).
        for (Eigen::Index i = 0; i < x.rows(); ++i)
        {
            Index idx[64];
            double w[64];
            ASSERT_EQ(lattice.basis(x.row(i).transpose(), FfdOutside::zero, idx, w), 64);
            Vector3 reproduced = Vector3::Zero();
            double sum = 0.0;
            for (int k = 0; k < 64; ++k)
            {
                sum += w[k];
                reproduced += w[k] * lattice.control_points().row(idx[k]).transpose();
            }
            EXPECT_NEAR(sum, 1.0, 1e-14);
            EXPECT_LE((reproduced - x.row(i).transpose()).norm(), 1e-13);
        }
        // Affine control motion is reproduced everywhere, boundary included.
        for (const Eigen::Matrix3d& L : {rot, Eigen::Matrix3d(Vector3(1.3, 0.6, 1.1).asDiagonal())})
        {
            FfdDeformation ffd(lattice);
            ffd.fit(lattice.control_points(),
                    test::affine_displacements(lattice.control_points(), L, t));
            EXPECT_LE(
                (displacements(ffd, x) - test::affine_displacements(x, L, t)).cwiseAbs().maxCoeff(),
                1e-12);
        }
    }
}

TEST(FfdLattice, knot_insertion_halves_the_span_and_inverts_local_coordinates)
{
    const FfdLattice coarse(skewed_box(), {5, 5, 5});
    const FfdLattice fine = coarse.with_inserted_knot(1, 0.5);
    EXPECT_TRUE(fine.is_uniform(0) && fine.is_uniform(2) && !fine.is_uniform(1));
    EXPECT_EQ(fine.counts()[1], 6);
    EXPECT_EQ(fine.knot_span(1, 0.3), std::make_pair(0.0, 0.5));
    EXPECT_EQ(fine.knot_span(1, 0.7), std::make_pair(0.5, 1.0));
    EXPECT_EQ(fine.knot_span(1, 1.5), std::make_pair(1.0, 2.0));
    // The domain stays [0, 2]: the same box point has the same parameter (Newton, skewed box).
    const Vector3 u(0.3, 0.4, 0.55);
    const Vector3 x = fine.box().origin + fine.box().axes * u;
    EXPECT_LE((fine.local_coordinates(x) - 2.0 * u).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE((fine.local_coordinates(x) - coarse.local_coordinates(x)).cwiseAbs().maxCoeff(),
              1e-12);
}

TEST(FfdLattice, rejects_bad_knots_and_insertions)
{
    const FfdLattice lattice(FfdBox{}, {4, 4, 4});
    EXPECT_THROW(lattice.with_inserted_knot(3, 0.5), InvalidInput);
    EXPECT_THROW(lattice.with_inserted_knot(0, 0.0), InvalidInput);  // existing knot
    EXPECT_THROW(lattice.with_inserted_knot(0, 1.0), InvalidInput);  // domain end
    EXPECT_THROW(lattice.with_inserted_knot(0, -0.5), InvalidInput); // outside the domain
    EXPECT_THROW(lattice.with_inserted_knot(0, std::nan("")), InvalidInput);
    const std::vector<double> ok = {-3, -2, -1, 0, 1, 2, 3, 4};
    EXPECT_NO_THROW(FfdLattice(FfdBox{}, {ok, ok, ok}));
    EXPECT_TRUE(FfdLattice(FfdBox{}, {ok, ok, ok}).is_uniform(0));
    const std::vector<double> short_knots = {0, 1, 2, 3, 4, 5, 6};
    const std::vector<double> repeated = {-3, -2, -1, 0, 0, 2, 3, 4};
    const std::vector<double> nan_knot = {-3, -2, -1, 0, std::nan(""), 2, 3, 4};
    EXPECT_THROW(FfdLattice(FfdBox{}, {ok, short_knots, ok}), InvalidInput);
    EXPECT_THROW(FfdLattice(FfdBox{}, {ok, ok, repeated}), InvalidInput);
    EXPECT_THROW(FfdLattice(FfdBox{}, {nan_knot, ok, ok}), InvalidInput);
}

} // namespace meshmorph
