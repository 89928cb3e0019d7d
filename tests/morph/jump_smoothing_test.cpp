// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of smooth_jumps() (src/meshmorph/morph/jump_smoothing.*): a box whose top face moves
// up on one half and stays on the other, so that the prescription jumps along the middle.
#include <algorithm>
#include <cstdlib>

#include <gtest/gtest.h>

#include "helpers.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/jump_smoothing.h"
#include "meshmorph/morph/jump_smoothing_guard.h"
#include "meshmorph/parallel/communicator.h"
#include "meshmorph/quality/face_orthogonality.h"

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
    const JumpSmoothing s =
        smooth_jumps(box.mesh, box.mesh.points, box.constrained, box.values, after);
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

TEST(JumpSmoothing, a_reach_beyond_the_cap_is_not_smoothed_and_says_how_far)
{
    // The smoothing is for a band: with more points within reach of the jumps than the cap
    // (here a cap of 10 points), the field is left as fitted and the count reported.
    const SteppedBox box;
    const Points before = box.nearest_field();
    Points after = before;
    const JumpSmoothing s =
        smooth_jumps(box.mesh, box.mesh.points, box.constrained, box.values, after, 10);
    ASSERT_GT(s.jump_constraints, 0);
    EXPECT_GT(s.skipped_reach, 10);
    EXPECT_EQ(s.band_points, 0);
    EXPECT_EQ(after, before);
    Points uncapped = before;
    const JumpSmoothing full =
        smooth_jumps(box.mesh, box.mesh.points, box.constrained, box.values, uncapped);
    EXPECT_EQ(full.skipped_reach, 0);
    EXPECT_GT(full.band_points, 0);
}

TEST(JumpSmoothing, spreads_the_jump_within_the_range_of_its_data)
{
    const SteppedBox box;
    Points d = box.nearest_field();
    smooth_jumps(box.mesh, box.mesh.points, box.constrained, box.values, d);
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
    smooth_jumps(box.mesh, box.mesh.points, box.constrained, box.values, once);
    smooth_jumps(box.mesh, box.mesh.points, box.constrained, 2.0 * box.values, twice);
    EXPECT_LE((twice - 2.0 * once).cwiseAbs().maxCoeff(), 1e-14 * lift);
}

TEST(JumpSmoothing, does_nothing_where_the_prescription_has_no_jump)
{
    SteppedBox box;
    box.values.col(2).setConstant(lift); // every boundary point lifted alike: no jump
    Points d = Points::Constant(box.mesh.points.rows(), 3, 0.0);
    d.col(2).setConstant(lift);
    const Points before = d;
    const JumpSmoothing s = smooth_jumps(box.mesh, box.mesh.points, box.constrained, box.values, d);
    EXPECT_EQ(s.jump_constraints, 0);
    EXPECT_EQ(s.band_points, 0);
    EXPECT_EQ(d, before);
}

TEST(JumpSmoothing, its_transpose_is_the_adjoint_of_the_smoothing)
{
    // The smoothing is linear in the field: <w, S d> = <S^T w, d> for any d and w.
    const SteppedBox box;
    std::srand(7);
    const Points d = Points::Random(box.mesh.points.rows(), 3);
    const Points w = Points::Random(box.mesh.points.rows(), 3);
    Points smoothed = d;
    const JumpSmoothing s =
        smooth_jumps(box.mesh, box.mesh.points, box.constrained, box.values, smoothed);
    ASSERT_GT(s.band_points, 0);
    Points transposed = w;
    smooth_jumps_transpose(box.mesh, box.mesh.points, box.constrained, box.values, transposed);
    const double forward = (w.array() * smoothed.array()).sum();
    const double reverse = (transposed.array() * d.array()).sum();
    EXPECT_NEAR(forward, reverse, 1e-12 * (w.norm() * d.norm()));
    for (const Index p : s.band)
        EXPECT_EQ(transposed.row(p).norm(), 0.0) << "band point " << p;
}

//! The largest non-orthogonality [deg] of the internal faces of `mesh` beside a cell with a
//! point of `band` (computed afresh, from the whole mesh's geometry).
double band_non_orthogonality(const PolyMesh& mesh, const std::vector<Index>& band)
{
    const MeshGeometry g = compute_geometry(mesh);
    std::vector<char> in_band(std::size_t(mesh.n_points()), 0);
    for (const Index p : band)
        in_band[std::size_t(p)] = 1;
    std::vector<char> touched(std::size_t(mesh.n_cells), 0);
    for (Index f = 0; f < mesh.n_faces(); ++f)
        for (const Index p : mesh.faces[f])
            if (in_band[std::size_t(p)] != 0)
            {
                touched[std::size_t(mesh.owner[std::size_t(f)])] = 1;
                if (mesh.is_internal_face(f))
                    touched[std::size_t(mesh.neighbour[std::size_t(f)])] = 1;
            }
    double largest = 0.0;
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
        if (touched[std::size_t(mesh.owner[std::size_t(f)])] != 0 ||
            touched[std::size_t(mesh.neighbour[std::size_t(f)])] != 0)
            largest = std::max(largest,
                               non_orthogonality_degrees(internal_face_orthogonality(mesh, g, f)));
    return largest;
}

//! The guard on the stepped box: the trial mesh at x0 + `applied` (band rows: `applied`'s),
//! with `other` as the band's alternative. Returns the choice; trial and applied updated.
JumpSmoothingChoice guard(const SteppedBox& box, const JumpSmoothing& s, Points& applied,
                          PolyMesh& trial, MeshGeometry& geometry)
{
    trial = box.mesh;
    trial.points = box.mesh.points + applied;
    const CompactList cells = cell_faces(trial);
    geometry = compute_geometry(trial, cells);
    return choose_jump_smoothing(trial, cells, geometry, box.mesh.points, s, applied,
                                 parallel::Communicator::world());
}

TEST(JumpSmoothingGuard, keeps_the_field_with_the_lower_non_orthogonality_either_way)
{
    const SteppedBox box;
    const Points fitted = box.nearest_field();
    Points smoothed = fitted;
    const JumpSmoothing s =
        smooth_jumps(box.mesh, box.mesh.points, box.constrained, box.values, smoothed);
    ASSERT_GT(s.band_points, 0);
    PolyMesh with_fitted = box.mesh, with_smoothed = box.mesh;
    with_fitted.points += fitted;
    with_smoothed.points += smoothed;
    const double fitted_max = band_non_orthogonality(with_fitted, s.band);
    const double smoothed_max = band_non_orthogonality(with_smoothed, s.band);
    ASSERT_LT(smoothed_max, fitted_max - 1.0) << "the jump in one column shears it most";

    // As the morph calls it: the smoothed field applied, the fitted one the alternative.
    Points applied = smoothed;
    PolyMesh trial;
    MeshGeometry geometry;
    JumpSmoothingChoice c = guard(box, s, applied, trial, geometry);
    EXPECT_TRUE(c.compared && c.kept);
    EXPECT_EQ(applied, smoothed);
    EXPECT_DOUBLE_EQ(c.smoothed.max_non_ortho, smoothed_max);
    EXPECT_DOUBLE_EQ(c.fitted.max_non_ortho, fitted_max);

    // The roles swapped (the worse field applied): the alternative is put back, and the
    // trial mesh and its geometry are exactly those of the field kept.
    JumpSmoothing swapped = s;
    for (std::size_t i = 0; i < s.band.size(); ++i)
        swapped.fitted.row(Eigen::Index(i)) = smoothed.row(s.band[i]);
    applied = fitted;
    c = guard(box, swapped, applied, trial, geometry);
    EXPECT_TRUE(c.compared && !c.kept);
    EXPECT_EQ(applied, smoothed);
    EXPECT_EQ(trial.points, Points(box.mesh.points + smoothed));
    const MeshGeometry fresh = compute_geometry(trial);
    EXPECT_EQ(geometry.face_centres, fresh.face_centres);
    EXPECT_EQ(geometry.face_areas, fresh.face_areas);
    EXPECT_EQ(geometry.cell_centres, fresh.cell_centres);
    EXPECT_EQ(geometry.cell_volumes, fresh.cell_volumes);
}

TEST(JumpSmoothingGuard, does_not_keep_a_smoothing_that_changes_nothing)
{
    // Equal figures (within the margin): the fitted field stays, whatever the round-off.
    const SteppedBox box;
    Points applied = box.nearest_field();
    JumpSmoothing s = smooth_jumps(box.mesh, box.mesh.points, box.constrained, box.values, applied);
    for (std::size_t i = 0; i < s.band.size(); ++i)
        s.fitted.row(Eigen::Index(i)) = applied.row(s.band[i]);
    PolyMesh trial;
    MeshGeometry geometry;
    const JumpSmoothingChoice c = guard(box, s, applied, trial, geometry);
    EXPECT_TRUE(c.compared);
    EXPECT_FALSE(c.kept);
}

} // namespace
} // namespace meshmorph::morph
