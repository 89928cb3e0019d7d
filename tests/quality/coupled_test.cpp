// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the cyclic support: coupled_patches.h (transforms, the cells across coupled
// faces), coupled_points.h and the coupled-aware metrics on synthetic periodic blocks.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/quality/cell_determinant.h"
#include "meshmorph/quality/check_mesh.h"
#include "meshmorph/quality/coupled_points.h"
#include "meshmorph/quality/face_orthogonality.h"
#include "meshmorph/quality/face_weights.h"

using namespace meshmorph;

namespace
{

//! Couple the patches `a` and `b` (indices) as a cyclic pair.
void make_cyclic(PolyMesh& mesh, std::size_t a, std::size_t b)
{
    for (auto [p, n] : {std::pair{a, b}, std::pair{b, a}})
    {
        mesh.patches[p].type = "cyclic";
        mesh.patches[p].entries = {{"neighbourPatch", mesh.patches[n].name}};
    }
}

//! A block of nx x 2 x 2 cells over [0, 4] x [0, 1] x [0, 1], cells growing along x, periodic
//! in x (xMin/xMax cyclic).
PolyMesh periodic_block(int nx)
{
    PolyMesh mesh = test::make_block_mesh(
        nx, 2, 2, [](double u, double v, double w) { return Vector3(4 * u * u, v, w); });
    make_cyclic(mesh, 0, 1);
    return mesh;
}

} // namespace

TEST(CoupledPatches, translation_brings_the_far_cell_across)
{
    const PolyMesh mesh = periodic_block(4);
    const MeshGeometry g = compute_geometry(mesh);
    const std::vector<CyclicPatch> cyclics = cyclic_patches(mesh, g);
    ASSERT_EQ(cyclics.size(), 2u);
    EXPECT_TRUE(cyclics[0].owner());
    EXPECT_FALSE(cyclics[1].owner());
    ASSERT_EQ(cyclics[0].separation.size(), 1u); // one uniform separation
    EXPECT_NEAR(cyclics[0].separation[0].x(), 4, 1e-12);
    EXPECT_NEAR(cyclics[1].separation[0].x(), -4, 1e-12);

    const CoupledFaces coupled = coupled_faces(mesh, g, cyclics);
    const Patch& x_min = mesh.patches[0];
    const Index b = x_min.start_face - mesh.n_internal_faces();
    // Across xMin lies the last cell of the row, moved back by the period.
    const Index last = mesh.owner[static_cast<std::size_t>(mesh.patches[1].start_face)];
    EXPECT_NEAR(coupled.neighbour_cell_centres(b, 0), g.cell_centres(last, 0) - 4, 1e-12);
    EXPECT_EQ(coupled.neighbour_cell_volumes[b], g.cell_volumes[last]);
    // Statistics: internal faces and the owner side only.
    const std::vector<char> summed = coupled.statistics_faces();
    EXPECT_TRUE(summed[static_cast<std::size_t>(x_min.start_face)]);
    EXPECT_FALSE(summed[static_cast<std::size_t>(mesh.patches[1].start_face)]);
    EXPECT_FALSE(summed[static_cast<std::size_t>(mesh.patches[2].start_face)]);
}

TEST(CoupledPatches, metrics_measure_cyclic_faces_against_the_cell_across)
{
    const PolyMesh mesh = periodic_block(4);
    const MeshGeometry g = compute_geometry(mesh);
    const CoupledFaces coupled = coupled_faces(mesh, g, cyclic_patches(mesh, g));
    const Index f = mesh.patches[0].start_face;
    const Index wall = mesh.patches[2].start_face;
    EXPECT_NEAR(face_orthogonality(mesh, g, coupled)[f], 1, 1e-12);
    // The first cell is 1/16 wide, the last 7/4: the face sits far from the middle.
    const double first = 0.25 * 0.25 * 4, last = 4 - 0.75 * 0.75 * 4;
    const Eigen::VectorXd w = face_weights(mesh, g, coupled);
    EXPECT_NEAR(w[f], first / (first + last), 1e-12);
    EXPECT_EQ(w[wall], 1.0);
    EXPECT_NEAR(face_volume_ratio(mesh, g.cell_volumes, coupled)[f], first / last, 1e-12);
}

TEST(CoupledPatches, determinant_counts_cyclic_faces)
{
    // One cell between cyclics in x and y, empty in z: without the coupling no face counts
    // and the determinant is 0; with it diag(2, 2, 1) / 8 (the empty direction counts 1).
    PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    make_cyclic(mesh, 0, 1);
    make_cyclic(mesh, 2, 3);
    mesh.patches[4].type = mesh.patches[5].type = "empty";
    const MeshGeometry g = compute_geometry(mesh);
    const CompactList cf = cell_faces(mesh);
    const MeshDirections dirs = mesh_directions(mesh, g.face_areas);
    const Eigen::VectorXd mag = face_area_magnitudes(g);
    EXPECT_EQ(cell_determinant(mesh, cf, g, dirs, mag)[0], 0.0);
    const CoupledFaces coupled = coupled_faces(mesh, g, cyclic_patches(mesh, g));
    EXPECT_NEAR(cell_determinant(mesh, cf, g, dirs, mag, coupled)[0], 0.5, 1e-12);
}

TEST(CoupledPoints, opposite_faces_match_and_a_moved_point_does_not)
{
    PolyMesh mesh = periodic_block(3);
    const MeshGeometry g = compute_geometry(mesh);
    const std::vector<CyclicPatch> cyclics = cyclic_patches(mesh, g);
    const CoupledPointMatch match = coupled_point_match(mesh, g, cyclics);
    EXPECT_TRUE(match.mismatched_faces.empty());
    EXPECT_LT(match.average_mismatch, 1e-12);

    // Move a point of xMax's first face two cells along y, further than the tolerance (the
    // largest distance of a vertex of the partner face from its centre).
    const Index f = mesh.patches[1].start_face;
    mesh.points(mesh.faces[f][1], 1) += 1.0;
    const MeshGeometry moved = compute_geometry(mesh);
    const CoupledPointMatch bad = coupled_point_match(mesh, moved, cyclic_patches(mesh, moved));
    // The point is shared by two faces; each is reported on the owner side (xMin).
    ASSERT_EQ(bad.mismatched_faces.size(), 2u);
    for (Index face : bad.mismatched_faces)
    {
        EXPECT_GE(face, mesh.patches[0].start_face);
        EXPECT_LT(face, mesh.patches[0].start_face + mesh.patches[0].n_faces);
    }
    const QualityReport r = check_mesh(mesh, {});
    EXPECT_NE(r.text.find("  **Error in coupled point location: 2 faces have their 0th or "
                          "consecutive vertex not opposite their coupled equivalent."),
              std::string::npos)
        << r.text;
}

TEST(CoupledPatches, rotational_transform_turns_about_the_axis)
{
    // A quarter ring about z, its two radial ends (yMin in y = 0, yMax in x = 0) coupled by
    // a 90-degree rotation: each side's transform must carry the other's face centres onto
    // its own, and the points must match.
    PolyMesh mesh = test::make_block_mesh(2, 2, 1,
                                          [](double u, double v, double w)
                                          {
                                              const double r = 1 + u, t = v * M_PI / 2;
                                              return Vector3(r * std::cos(t), r * std::sin(t), w);
                                          });
    make_cyclic(mesh, 2, 3);
    for (std::size_t p : {2u, 3u})
    {
        mesh.patches[p].entries.emplace_back("transform", "rotational");
        mesh.patches[p].entries.emplace_back("rotationAxis", "(0 0 1)");
        mesh.patches[p].entries.emplace_back("rotationCentre", "(0 0 0)");
    }
    const MeshGeometry g = compute_geometry(mesh);
    const std::vector<CyclicPatch> cyclics = cyclic_patches(mesh, g);
    ASSERT_EQ(cyclics.size(), 2u);
    for (const CyclicPatch& c : cyclics)
    {
        const Patch& own = mesh.patches[static_cast<std::size_t>(c.patch)];
        const Patch& nbr = mesh.patches[static_cast<std::size_t>(c.neighbour)];
        for (Index i = 0; i < own.n_faces; ++i)
        {
            const Vector3 there = g.face_centres.row(nbr.start_face + i).transpose();
            const Vector3 here = g.face_centres.row(own.start_face + i).transpose();
            EXPECT_LT((c.transform_position(there, i) - here).norm(), 1e-12);
        }
    }
    const CoupledPointMatch match = coupled_point_match(mesh, g, cyclics);
    EXPECT_TRUE(match.mismatched_faces.empty());
    EXPECT_LT(match.average_mismatch, 1e-12);
}
