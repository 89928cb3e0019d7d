// SPDX-License-Identifier: GPL-3.0-or-later
// first_inversion_step: exact on motions whose inversion is known (a cube squashed flat, a
// tet's apex pushed through its base), none for motions that never invert (a translation, a
// linearised rotation), and close to checkMesh's own verdict where the centres differ.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "helpers.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/inversion_step.h"
#include "shape_meshes.h"

namespace meshmorph
{
namespace
{

constexpr double inf = std::numeric_limits<double>::infinity();

double estimate(const PolyMesh& mesh, const Points& dx, double limit = inf)
{
    const CompactList cf = cell_faces(mesh);
    return first_inversion_step(mesh, cf, compute_geometry(mesh, cf), dx, limit);
}

//! The checker's first invalid step along dx, by bisection to 1e-12 (the test's reference).
double checked_inversion(PolyMesh mesh, const Points& dx, double hi)
{
    const Points x = mesh.points;
    const CompactList cf = cell_faces(mesh);
    const auto invalid = [&](double t)
    {
        mesh.points = x + t * dx;
        const InvalidCells c = count_invalid_cells(mesh, compute_geometry(mesh, cf));
        return c.negative_volume_cells + c.wrong_pyramids > 0;
    };
    double lo = 0.0;
    EXPECT_TRUE(invalid(hi));
    while (hi - lo > 1e-12)
        (invalid(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
    return hi;
}

TEST(InversionStep, a_cube_squashed_flat_inverts_when_its_top_reaches_its_bottom)
{
    const PolyMesh cube = test::make_box_mesh(1, 1, 1);
    Points dx = Points::Zero(cube.n_points(), 3);
    for (Index p = 0; p < cube.n_points(); ++p)
        if (cube.points(p, 2) > 0.5)
            dx(p, 2) = -0.25; // the top moves down 0.25 per unit step: flat at t = 4
    EXPECT_NEAR(estimate(cube, dx), 4.0, 1e-12);
    EXPECT_EQ(estimate(cube, dx, 3.9), inf);
    EXPECT_NEAR(checked_inversion(cube, dx, 8.0), 4.0, 1e-9);
}

TEST(InversionStep, a_tet_inverts_when_its_apex_crosses_its_base)
{
    Points p(4, 3);
    p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.3, 1;
    const PolyMesh tet = test::mesh_from_cells(p, {test::tet_loops({0, 1, 2, 3})});
    Points dx = Points::Zero(4, 3);
    dx.row(3) << 0.1, -0.1, -0.5; // the apex reaches the base plane z = 0 at t = 2
    EXPECT_NEAR(estimate(tet, dx), 2.0, 1e-12);
    EXPECT_NEAR(checked_inversion(tet, dx, 4.0), 2.0, 1e-9);
}

TEST(InversionStep, translations_and_linearised_rotations_never_invert)
{
    const PolyMesh box = test::make_box_mesh(3, 2, 2);
    Points shift(box.n_points(), 3);
    shift.rowwise() = Eigen::RowVector3d(1.0, -2.0, 0.5);
    EXPECT_EQ(estimate(box, shift), inf);
    // x + t (w x (x - c)): every volume scales by det(I + t W) = 1 + t^2 |w|^2 > 0.
    const Vector3 w(0.3, -0.2, 1.0), c(0.5, 0.5, 0.5);
    Points spin(box.n_points(), 3);
    for (Index i = 0; i < box.n_points(); ++i)
        spin.row(i) = w.cross(box.points.row(i).transpose() - c).transpose();
    EXPECT_EQ(estimate(box, spin), inf);
}

TEST(InversionStep, is_close_to_the_checkers_verdict_for_a_point_pushed_through_its_cells)
{
    // One interior point of a 4^3 box pushed diagonally: its cells' faces warp, and
    // checkMesh's weighted centres move other than linearly.
    const PolyMesh box = test::make_box_mesh(4, 4, 4);
    Points dx = Points::Zero(box.n_points(), 3);
    Index moved = -1;
    for (Index i = 0; i < box.n_points(); ++i)
        if ((box.points.row(i) - Eigen::RowVector3d(0.5, 0.5, 0.5)).norm() < 1e-9)
            moved = i;
    ASSERT_GE(moved, 0);
    dx.row(moved) << 0.3, 0.2, 0.1;
    const double e = estimate(box, dx);
    const double checked = checked_inversion(box, dx, 10.0);
    EXPECT_NEAR(e / checked, 1.0, 0.05) << "estimate " << e << ", checker " << checked;
    // The same in parallel and serial: a minimum over cells.
    EXPECT_EQ(estimate(box, dx), e);
}

} // namespace
} // namespace meshmorph
