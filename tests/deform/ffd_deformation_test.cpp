// SPDX-License-Identifier: GPL-3.0-or-later
// Properties of the B-spline lattice and classic FFD: linear precision (affine motions are
// reproduced everywhere in the box, boundary included), outside policies, Newton local
// coordinates on parallelepiped lattices, bad input.
#include <gtest/gtest.h>

#include <omp.h>

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

} // namespace meshmorph
