// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/core/poly_mesh.h"

#include <gtest/gtest.h>

#include "helpers.h"

using namespace meshmorph;

namespace
{
// Face area vector by the right-hand rule about the vertex average.
Vector3 area_vector(const PolyMesh& mesh, Index f)
{
    const auto face = mesh.faces[f];
    Vector3 centre = Vector3::Zero();
    for (Index p : face)
        centre += mesh.points.row(p).transpose();
    centre /= static_cast<double>(face.size());
    Vector3 area = Vector3::Zero();
    for (std::size_t i = 0; i < face.size(); ++i)
    {
        const Vector3 a = mesh.points.row(face[i]).transpose();
        const Vector3 b = mesh.points.row(face[(i + 1) % face.size()]).transpose();
        area += 0.5 * (b - a).cross(centre - a);
    }
    return area;
}
} // namespace

TEST(PolyMesh, block_mesh_counts_match_structured_formulas)
{
    const PolyMesh mesh = test::make_box_mesh(3, 4, 5);
    EXPECT_EQ(mesh.n_points(), 4 * 5 * 6);
    EXPECT_EQ(mesh.n_cells, 60);
    EXPECT_EQ(mesh.n_internal_faces(), 2 * 4 * 5 + 3 * 3 * 5 + 3 * 4 * 4);
    EXPECT_EQ(mesh.n_faces(), mesh.n_internal_faces() + 2 * (4 * 5 + 3 * 5 + 3 * 4));
    EXPECT_EQ(mesh.patches.back().start_face + mesh.patches.back().n_faces, mesh.n_faces());
}

TEST(PolyMesh, block_mesh_faces_upper_triangular_and_oriented)
{
    const PolyMesh mesh = test::make_box_mesh(3, 2, 2);
    const CompactList cf = cell_faces(mesh);
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
        EXPECT_LT(mesh.owner[f], mesh.neighbour[f]);
    for (Index f = 1; f < mesh.n_internal_faces(); ++f)
    {
        const bool ordered =
            mesh.owner[f - 1] < mesh.owner[f] ||
            (mesh.owner[f - 1] == mesh.owner[f] && mesh.neighbour[f - 1] < mesh.neighbour[f]);
        EXPECT_TRUE(ordered) << "face " << f;
    }
    // Every cell is closed: the sum of its outward area vectors vanishes.
    for (Index c = 0; c < mesh.n_cells; ++c)
    {
        Vector3 sum = Vector3::Zero();
        for (Index f : cf[c])
            sum += (mesh.owner[f] == c ? 1.0 : -1.0) * area_vector(mesh, f);
        EXPECT_LT(sum.norm(), 1e-14) << "cell " << c;
    }
    // Boundary faces point out of the unit box.
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
    {
        const Vector3 a = area_vector(mesh, f);
        Vector3 centre = Vector3::Zero();
        for (Index p : mesh.faces[f])
            centre += mesh.points.row(p).transpose() / 4.0;
        EXPECT_GT(a.dot(centre - Vector3(0.5, 0.5, 0.5)), 0.0) << "face " << f;
    }
}

TEST(PolyMesh, which_patch_and_patch_points)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    EXPECT_EQ(mesh.which_patch(0), -1);
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
    {
        const Patch& patch = mesh.patches[p];
        EXPECT_EQ(mesh.which_patch(patch.start_face), static_cast<Index>(p));
        EXPECT_EQ(mesh.which_patch(patch.start_face + patch.n_faces - 1), static_cast<Index>(p));
        EXPECT_EQ(patch_points(mesh, patch).size(), 9u);
    }
    EXPECT_EQ(mesh.find_patch("zMax"), 5);
    EXPECT_EQ(mesh.find_patch("nope"), -1);
    // First appearance order: the first face's vertices come first.
    const std::vector<Index> pts = patch_points(mesh, mesh.patches[0]);
    const auto first = mesh.faces[mesh.patches[0].start_face];
    EXPECT_TRUE(std::equal(first.begin(), first.end(), pts.begin()));
}

TEST(PolyMesh, cell_points_of_hex_are_eight)
{
    const PolyMesh mesh = test::make_box_mesh(2, 1, 1);
    const CompactList cp = cell_points(mesh, cell_faces(mesh));
    ASSERT_EQ(cp.size(), 2);
    EXPECT_EQ(cp.item_size(0), 8);
    EXPECT_EQ(cp.item_size(1), 8);
    const std::vector<char> mask = boundary_point_mask(mesh);
    EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 12);
}
