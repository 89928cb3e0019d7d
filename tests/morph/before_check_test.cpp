// SPDX-License-Identifier: GPL-3.0-or-later
// The check before a morph (morph/before_check.h): run on its own thread, it reports what
// the check run in place reports, its invalid counts are the report's, and an error of the
// check reaches the caller; it hands over its summary and topology, not its cell fields.
#include <gtest/gtest.h>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/before_check.h"
#include "meshmorph/quality/check_mesh.h"
#include "meshmorph/quality/scaled_jacobian.h"

namespace meshmorph::morph
{

TEST(BeforeCheck, on_its_own_thread_reports_what_the_check_in_place_reports)
{
    PolyMesh mesh = test::make_box_mesh(6, 5, 4);
    // An inverted corner cell, so that the invalid counts are not zero.
    mesh.points.row(0) = Eigen::RowVector3d(0.4, 0.4, 0.4);
    const CompactList cf = cell_faces(mesh);
    CheckMeshSettings settings;
    settings.scaled_jacobian = true;
    const QualityReport direct = check_mesh(mesh, cf, compute_geometry(mesh, cf), settings);
    BeforeCheck before(mesh, cf, settings, Decomposition{}, "");
    const QualityReport& threaded = before.report();
    EXPECT_EQ(threaded.text, direct.text);
    EXPECT_EQ(threaded.failed_checks, direct.failed_checks);
    EXPECT_EQ(threaded.max_non_orthogonality, direct.max_non_orthogonality);
    EXPECT_EQ(threaded.min_scaled_jacobian, direct.min_scaled_jacobian);
    const InvalidCells invalid = before.invalid();
    EXPECT_EQ(invalid.negative_volume_cells, direct.negative_volume_cells);
    EXPECT_EQ(invalid.wrong_pyramids, direct.incorrectly_oriented_face_pyramids);
    EXPECT_GT(invalid.wrong_pyramids, 0);
    EXPECT_GE(before.waited_seconds(), 0.0);
}

TEST(BeforeCheck, hands_over_the_summary_and_the_topology_without_the_cell_fields)
{
    const PolyMesh mesh = test::make_box_mesh(4, 3, 3);
    const CompactList cf = cell_faces(mesh);
    CheckMeshSettings settings;
    settings.scaled_jacobian = true;
    const QualityReport direct = check_mesh(mesh, cf, compute_geometry(mesh, cf), settings);
    ASSERT_EQ(direct.cell_skewness.size(), mesh.n_cells);
    BeforeCheck before(mesh, cf, settings, Decomposition{}, "");
    const QualityReport taken = before.take_report();
    EXPECT_EQ(taken.text, direct.text);
    EXPECT_EQ(taken.min_scaled_jacobian, direct.min_scaled_jacobian);
    EXPECT_EQ(taken.n_topology_checks, direct.n_topology_checks);
    ASSERT_TRUE(taken.jacobian_corners); // what the check after the morph reuses
    EXPECT_EQ(taken.jacobian_corners->types.size(), std::size_t(mesh.n_cells));
    // Per-cell fields are the check after's business: none is kept from before.
    EXPECT_EQ(taken.cell_non_orthogonality.size(), 0);
    EXPECT_EQ(taken.cell_skewness.size(), 0);
    EXPECT_EQ(taken.cell_aspect_ratio.size(), 0);
    EXPECT_EQ(taken.cell_determinant.size(), 0);
    EXPECT_EQ(taken.cell_scaled_jacobian.size(), 0);
}

TEST(BeforeCheck, an_error_of_the_check_reaches_the_caller)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    const CompactList wrong = cell_faces(test::make_box_mesh(3, 2, 2)); // 12 cells, not 8
    BeforeCheck before(mesh, wrong, CheckMeshSettings{}, Decomposition{}, "");
    EXPECT_THROW(before.report(), InvalidInput);
}

TEST(BeforeCheck, a_check_already_done_is_returned_as_it_is)
{
    QualityReport done;
    done.negative_volume_cells = 3;
    done.incorrectly_oriented_face_pyramids = 5;
    BeforeCheck before(done);
    EXPECT_EQ(before.report().negative_volume_cells, 3);
    EXPECT_EQ(before.invalid().wrong_pyramids, 5);
    EXPECT_EQ(before.waited_seconds(), 0.0);
}

} // namespace meshmorph::morph
