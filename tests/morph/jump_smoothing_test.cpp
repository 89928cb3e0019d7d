// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of smooth_jumps() (src/meshmorph/morph/jump_smoothing.*): a box whose top face moves
// up on one half and stays on the other, so that the prescription jumps along the middle.
#include <algorithm>

#include <gtest/gtest.h>

#include "helpers.h"
#include "meshmorph/morph/jump_smoothing.h"

namespace meshmorph::morph
{
namespace
{

constexpr double lift = 0.01;

//! A slab [0,1] x [0,0.02] x [0,0.2] (96 x 2 x 20 cells) whose top and bottom faces are
//! constrained (its sides are free): the top face's points with x > 0.5 lifted by `lift`,
//! every other one fixed, so the prescription jumps along x = 0.5 on the top. The band
//! (2.5% of the lifted points' extent: 0.0126) is wider than the cells (0.0104 in x, 0.01
//! in y and z), so it holds the free points just below the jump.
struct SteppedBox
{
    PolyMesh mesh = test::make_box_mesh(96, 2, 20, Vector3(0, 0, 0), Vector3(1, 0.02, 0.2));
    std::vector<Index> constrained;
    Points values;

    SteppedBox()
    {
        for (Index p = 0; p < mesh.points.rows(); ++p)
            if (mesh.points(p, 2) < 1e-12 || mesh.points(p, 2) > 0.2 - 1e-12)
                constrained.push_back(p);
        values = Points::Zero(Eigen::Index(constrained.size()), 3);
        for (std::size_t i = 0; i < constrained.size(); ++i)
        {
            const Eigen::RowVector3d x = mesh.points.row(constrained[i]);
            if (x.z() > 0.2 - 1e-12 && x.x() > 0.5 + 1e-12)
                values(Eigen::Index(i), 2) = lift;
        }
    }

    //! A fitted field as an inverse-distance correction leaves it: the prescription at the
    //! constrained points, elsewhere the value of the nearest constrained point (the whole
    //! jump in one layer of cells).
    Points nearest_field() const
    {
        Points d = Points::Zero(mesh.points.rows(), 3);
        for (Index p = 0; p < mesh.points.rows(); ++p)
        {
            double best = 1e300;
            for (std::size_t i = 0; i < constrained.size(); ++i)
            {
                const double r = (mesh.points.row(p) - mesh.points.row(constrained[i])).norm();
                if (r < best)
                {
                    best = r;
                    d.row(p) = values.row(Eigen::Index(i));
                }
            }
        }
        return d;
    }
};

TEST(JumpSmoothing, changes_only_free_points_in_the_band_and_keeps_every_constraint)
{
    const SteppedBox box;
    const Points before = box.nearest_field();
    Points after = before;
    const JumpSmoothing s = smooth_jumps(box.mesh, box.constrained, box.values, after);
    ASSERT_GT(s.jump_constraints, 0);
    ASSERT_GT(s.band_points, 0);
    Index changed = 0;
    for (Index p = 0; p < box.mesh.points.rows(); ++p)
        if (after.row(p) != before.row(p))
            ++changed;
    EXPECT_LE(changed, s.band_points);
    EXPECT_GT(changed, 0);
    for (const Index p : box.constrained)
        EXPECT_EQ(after.row(p), before.row(p)) << "constrained point " << p;
    // Points farther from the jump than the band's width (along any path) keep the field.
    for (Index p = 0; p < box.mesh.points.rows(); ++p)
    {
        if (std::abs(box.mesh.points(p, 0) - 0.5) > s.width + 1e-12)
        {
            EXPECT_EQ(after.row(p), before.row(p)) << "point " << p << " outside the band";
        }
    }
}

TEST(JumpSmoothing, spreads_the_jump_within_the_range_of_its_data)
{
    const SteppedBox box;
    Points d = box.nearest_field();
    smooth_jumps(box.mesh, box.constrained, box.values, d);
    // A maximum principle: every value between the data's extremes; and the free point just
    // below the top face on the lifted side of the jump now moves less than the lift, the
    // one on the fixed side more than nothing: the shear is spread, not left in one column.
    EXPECT_GE(d.col(2).minCoeff(), 0.0);
    EXPECT_LE(d.col(2).maxCoeff(), lift);
    const auto point_at = [&](double x, double y, double z)
    {
        Index best = 0;
        for (Index p = 0; p < box.mesh.points.rows(); ++p)
            if ((box.mesh.points.row(p) - Eigen::RowVector3d(x, y, z)).norm() <
                (box.mesh.points.row(best) - Eigen::RowVector3d(x, y, z)).norm())
                best = p;
        return best;
    };
    const Index lifted_side = point_at(49.0 / 96.0, 0.01, 0.19); // below the jump's two sides
    const Index fixed_side = point_at(48.0 / 96.0, 0.01, 0.19);
    EXPECT_LT(d(lifted_side, 2), 0.99 * lift);
    EXPECT_GT(d(fixed_side, 2), 0.01 * lift);
    EXPECT_GT(d(lifted_side, 2), d(fixed_side, 2));
}

TEST(JumpSmoothing, is_linear_in_the_amplitude_of_the_motion)
{
    // Design variables add fields: twice the prescription and field, twice the result.
    const SteppedBox box;
    Points once = box.nearest_field();
    Points twice = 2.0 * once;
    smooth_jumps(box.mesh, box.constrained, box.values, once);
    smooth_jumps(box.mesh, box.constrained, 2.0 * box.values, twice);
    EXPECT_LE((twice - 2.0 * once).cwiseAbs().maxCoeff(), 1e-14 * lift);
}

TEST(JumpSmoothing, does_nothing_where_the_prescription_has_no_jump)
{
    SteppedBox box;
    box.values.col(2).setConstant(lift); // every boundary point lifted alike: no jump
    Points d = Points::Constant(box.mesh.points.rows(), 3, 0.0);
    d.col(2).setConstant(lift);
    const Points before = d;
    const JumpSmoothing s = smooth_jumps(box.mesh, box.constrained, box.values, d);
    EXPECT_EQ(s.jump_constraints, 0);
    EXPECT_EQ(s.band_points, 0);
    EXPECT_EQ(d, before);
}

} // namespace
} // namespace meshmorph::morph
