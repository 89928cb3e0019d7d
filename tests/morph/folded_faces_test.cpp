// SPDX-License-Identifier: GPL-3.0-or-later
// faces_folded_by_prescription() (src/meshmorph/morph/folded_faces.*) on a unit box of
// 4 x 4 x 4 hexahedra whose boundary points are all prescribed: a top face slid past its
// fixed edge folds exactly the faces next to that edge; a half turn of the whole box folds
// nothing, whether prescribed as a rotation or as the same displacements given as values
// (its faces turn over, but with their neighbours).
#include "meshmorph/morph/folded_faces.h"

#include <cmath>

#include <gtest/gtest.h>

#include "helpers.h"

namespace meshmorph::morph
{
namespace
{

//! Every boundary point of `mesh`, prescribed `motion(x)`; no rotation.
template <class Motion> Constraints every_boundary_point(const PolyMesh& mesh, const Motion& motion)
{
    std::vector<char> on(std::size_t(mesh.n_points()), 0);
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
        for (Index p : mesh.faces[f])
            on[std::size_t(p)] = 1;
    Constraints c;
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (on[std::size_t(p)])
            c.points.push_back(p);
    c.displacements.resize(Eigen::Index(c.points.size()), 3);
    for (std::size_t i = 0; i < c.points.size(); ++i)
        c.displacements.row(Eigen::Index(i)) =
            motion(Vector3(mesh.points.row(c.points[i]).transpose())).transpose();
    c.rotation_of.assign(c.points.size(), -1);
    return c;
}

Index faces_on(const FoldedFaces& folded, const std::string& patch)
{
    for (const PatchFaces& p : folded.by_patch)
        if (p.patch == patch)
            return p.faces;
    return 0;
}

TEST(FoldedFaces, a_top_slid_past_its_fixed_edge_folds_the_faces_along_that_edge)
{
    const PolyMesh mesh = test::make_box_mesh(4, 4, 4);
    // The top's points off its edges slide by -0.6 in x; its edges stay (as the conflict
    // rule `fixed` holds points shared with fixed sides). The column next to x = 0 has its
    // moved points at x = -0.35, past the edge: those 4 faces turn over. The other columns
    // only stretch or move whole.
    const auto inside_top = [](const Vector3& x)
    {
        const auto inside = [](double v) { return v > 1e-9 && v < 1 - 1e-9; };
        return x.z() > 1 - 1e-9 && inside(x.x()) && inside(x.y());
    };
    const Constraints c =
        every_boundary_point(mesh, [&](const Vector3& x)
                             { return inside_top(x) ? Vector3(-0.6, 0, 0) : Vector3(0, 0, 0); });
    const FoldedFaces folded =
        faces_folded_by_prescription(mesh, c, parallel::Communicator::world());
    EXPECT_EQ(folded.faces, 4);
    EXPECT_EQ(faces_on(folded, "zMax"), 4);
    ASSERT_FALSE(folded.meeting.empty());
    EXPECT_EQ(folded.meeting.front().patch, "xMin"); // every one of the 4 touches x = 0
    EXPECT_EQ(folded.meeting.front().faces, 4);
    EXPECT_NEAR(folded.example.x(), 0.125, 1e-12); // a face of the column at x in [0, 0.25]
    EXPECT_NE(describe(folded).find("folds 4 faces over: zMax (4 faces)"), std::string::npos)
        << describe(folded);
    EXPECT_NE(describe(folded).find("They meet xMin (4 faces)"), std::string::npos)
        << describe(folded);

    // Slid by less than a cell, nothing turns over.
    const Constraints short_slide =
        every_boundary_point(mesh, [&](const Vector3& x)
                             { return inside_top(x) ? Vector3(-0.2, 0, 0) : Vector3(0, 0, 0); });
    EXPECT_EQ(
        faces_folded_by_prescription(mesh, short_slide, parallel::Communicator::world()).faces, 0);
}

TEST(FoldedFaces, a_half_turn_folds_nothing_as_a_rotation_or_as_plain_displacements)
{
    const PolyMesh mesh = test::make_box_mesh(4, 4, 4);
    Motion turn;
    turn.type = MotionType::rotate;
    turn.origin = Vector3(0.5, 0.5, 0.5);
    turn.axis = Vector3::UnitZ();
    turn.angle_degrees = 180.0;
    Constraints c =
        every_boundary_point(mesh, [&](const Vector3& x) { return turn.displacement(x); });
    // As plain values: the four sides' area vectors point against their unmoved ones (the
    // premise), yet each turned with the faces beside it.
    std::size_t sides_turned = 0;
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
    {
        Vector3 a0 = Vector3::Zero(), a1 = Vector3::Zero();
        const auto face = mesh.faces[f];
        for (std::size_t k = 0; k < face.size(); ++k)
        {
            const Vector3 p = mesh.points.row(face[k]).transpose();
            const Vector3 q = mesh.points.row(face[(k + 1) % face.size()]).transpose();
            a0 += p.cross(q);
            a1 += (p + turn.displacement(p)).cross(q + turn.displacement(q));
        }
        sides_turned += a1.dot(a0) < 0 ? 1 : 0;
    }
    ASSERT_EQ(sides_turned, 4u * 16u);
    EXPECT_EQ(faces_folded_by_prescription(mesh, c, parallel::Communicator::world()).faces, 0);

    c.rotations = {turn};
    c.rotation_of.assign(c.points.size(), 0);
    EXPECT_EQ(faces_folded_by_prescription(mesh, c, parallel::Communicator::world()).faces, 0);
    EXPECT_EQ(describe(FoldedFaces{}), "");
}

} // namespace
} // namespace meshmorph::morph
