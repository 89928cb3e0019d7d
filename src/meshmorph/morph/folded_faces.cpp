// SPDX-License-Identifier: GPL-3.0-or-later
// Faces the prescription alone folds over.
#include "meshmorph/morph/folded_faces.h"

#include <algorithm>
#include <cstdint>
#include <numbers>
#include <span>
#include <sstream>

#include <Eigen/Geometry>

#include "meshmorph/mesh/patch_kinds.h"
#include "meshmorph/mesh/point_faces.h"

namespace meshmorph::morph
{

namespace
{

//! Per mesh point, its row in c.points (-1: not prescribed).
std::vector<Index> constraint_rows(Index n_points, const Constraints& c)
{
    std::vector<Index> row(std::size_t(n_points), -1);
    for (std::size_t i = 0; i < c.points.size(); ++i)
        row[std::size_t(c.points[i])] = Index(i);
    return row;
}

//! The area vector of a polygon: its triangles from the mean of its points. The sign test
//! needs no more than this (checkMesh's own centre differs only for warped faces).
template <class Position> Vector3 polygon_area(std::span<const Index> face, const Position& x)
{
    Vector3 mean = Vector3::Zero();
    for (Index p : face)
        mean += x(p);
    mean /= double(face.size());
    Vector3 area = Vector3::Zero();
    for (std::size_t k = 0; k < face.size(); ++k)
        area += (x(face[k]) - mean).cross(x(face[(k + 1) % face.size()]) - mean);
    return 0.5 * area;
}

//! The sum of a face's squared edge lengths: the scale below which an area is zero.
double squared_perimeter_scale(std::span<const Index> face, const Points& x)
{
    double sum = 0.0;
    for (std::size_t k = 0; k < face.size(); ++k)
        sum += (x.row(face[(k + 1) % face.size()]) - x.row(face[k])).squaredNorm();
    return sum;
}

//! The rotation a prescription row turns its neighbourhood by (identity unless `rotate`).
Eigen::Matrix3d rotation_of_row(const Constraints& c, Index row)
{
    const Index r = row < Index(c.rotation_of.size()) ? c.rotation_of[std::size_t(row)] : -1;
    if (r < 0)
        return Eigen::Matrix3d::Identity();
    const Motion& m = c.rotations[std::size_t(r)];
    return Eigen::AngleAxisd(m.angle_degrees * std::numbers::pi / 180.0, m.axis.normalized())
        .toRotationMatrix();
}

//! What the test of one face needs: the unmoved points and the prescription per point.
struct FoldTest
{
    const PolyMesh& mesh;
    const Constraints& c;
    std::vector<Index> row; //!< constraint_rows

    //! Every point prescribed, and at least one moves.
    bool moved_whole(std::span<const Index> face) const
    {
        bool moves = false;
        for (Index p : face)
        {
            const Index r = row[std::size_t(p)];
            if (r < 0)
                return false;
            moves = moves || !c.displacements.row(r).isZero(0.0);
        }
        return moves;
    }

    //! The largest prescribed displacement of the face's points.
    double largest_motion(std::span<const Index> face) const
    {
        double largest = 0.0;
        for (Index p : face)
            largest = std::max(largest, c.displacements.row(row[std::size_t(p)]).norm());
        return largest;
    }

    Vector3 area_before(std::span<const Index> face) const
    {
        return polygon_area(face,
                            [&](Index p) -> Vector3 { return mesh.points.row(p).transpose(); });
    }

    //! \pre moved_whole(face).
    Vector3 area_after(std::span<const Index> face) const
    {
        return polygon_area(
            face,
            [&](Index p) -> Vector3 {
                return (mesh.points.row(p) + c.displacements.row(row[std::size_t(p)])).transpose();
            });
    }

    //! \pre moved_whole(face). Its area vector points against the unmoved one, as turned by
    //! each rotation among its points' prescriptions (identity for the others): a face a
    //! `rotate` entry turns whole is not turned over, however far.
    bool turned_over(std::span<const Index> face) const
    {
        const Vector3 a0 = area_before(face);
        // Round-off of the area of a degenerate face carries no orientation.
        if (a0.norm() <= 1e-10 * squared_perimeter_scale(face, mesh.points))
            return false;
        const Vector3 a1 = area_after(face);
        for (Index p : face)
            if (a1.dot(rotation_of_row(c, row[std::size_t(p)]) * a0) > 0.0)
                return false;
        return true;
    }

    //! \pre turned_over(f). A face it shares an edge with, moved whole, that lay within 60
    //! degrees of it and now lies 90 or more away: f turned over against the surface beside
    //! it, a fold. A face turned whole with its neighbours (a half turn given as plain
    //! displacements, a surface bent round) is not folded.
    bool folded_against_a_neighbour(Index f, const CompactList& faces_of_point) const
    {
        const auto face = mesh.faces[f];
        const Vector3 n0 = area_before(face).normalized();
        const Vector3 n1 = area_after(face);
        for (std::size_t k = 0; k < face.size(); ++k)
        {
            const Index p = face[k], q = face[(k + 1) % face.size()];
            for (Index g : faces_of_point[p])
            {
                const auto other = mesh.faces[g];
                if (g == f || std::find(other.begin(), other.end(), q) == other.end() ||
                    !moved_whole(other))
                    continue;
                if (area_before(other).normalized().dot(n0) > 0.5 &&
                    area_after(other).dot(n1) <= 0.0)
                    return true;
            }
        }
        return false;
    }
};

//! The boundary faces of the patches (processor faces are internal to the whole mesh).
std::vector<Index> patch_faces(const PolyMesh& mesh)
{
    std::vector<Index> faces;
    for (const Patch& p : mesh.patches)
        if (!is_processor_patch(p))
            for (Index f = p.start_face; f < p.start_face + p.n_faces; ++f)
                faces.push_back(f);
    return faces;
}

//! The patch a face lies on.
std::string patch_name_of(const PolyMesh& mesh, Index f)
{
    for (const Patch& p : mesh.patches)
        if (f >= p.start_face && f < p.start_face + p.n_faces)
            return p.name;
    return {};
}

//! `names` counted, summed over the ranks (every rank holds the same patches, in the same
//! order), the most first.
std::vector<PatchFaces> count_by_name(const PolyMesh& mesh, const std::vector<std::string>& names,
                                      const parallel::Communicator& comm)
{
    std::vector<std::string> all;
    for (const Patch& p : mesh.patches)
        if (!is_processor_patch(p))
            all.push_back(p.name);
    std::vector<PatchFaces> counts;
    for (const std::string& name : all)
    {
        const std::int64_t n = comm.sum(std::int64_t(std::count(names.begin(), names.end(), name)));
        if (n > 0)
            counts.push_back({name, Index(n)});
    }
    std::stable_sort(counts.begin(), counts.end(),
                     [](const PatchFaces& a, const PatchFaces& b) { return a.faces > b.faces; });
    return counts;
}

//! Per folded face, the other patches its points lie on (each once per face).
std::vector<std::string> patches_met(const PolyMesh& mesh, const std::vector<Index>& faces)
{
    std::vector<std::string> met;
    std::vector<char> on(std::size_t(mesh.n_points()), 0);
    for (const Patch& patch : mesh.patches)
    {
        if (is_processor_patch(patch))
            continue;
        std::fill(on.begin(), on.end(), 0);
        for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
            for (Index p : mesh.faces[f])
                on[std::size_t(p)] = 1;
        for (Index f : faces)
        {
            const bool own = f >= patch.start_face && f < patch.start_face + patch.n_faces;
            const auto points = mesh.faces[f];
            if (!own && std::any_of(points.begin(), points.end(),
                                    [&on](Index p) { return on[std::size_t(p)] != 0; }))
                met.push_back(patch.name);
        }
    }
    return met;
}

//! The centre of the face that moved the most, over the ranks (the rank holding the
//! largest motion sends it; the others add zeros).
Vector3 example_centre(const PolyMesh& mesh, const FoldTest& test, const std::vector<Index>& faces,
                       const parallel::Communicator& comm)
{
    double mine = -1.0;
    Index at = -1;
    for (Index f : faces)
        if (const double m = test.largest_motion(mesh.faces[f]); m > mine)
            mine = m, at = f;
    const double largest = comm.max(mine);
    const std::int64_t sender =
        comm.max(std::int64_t(at >= 0 && mine == largest ? comm.rank() : -1));
    Vector3 centre = Vector3::Zero();
    if (comm.rank() == sender)
    {
        for (Index p : mesh.faces[at])
            centre += mesh.points.row(p).transpose();
        centre /= double(mesh.faces.item_size(at));
    }
    for (int k = 0; k < 3; ++k)
        centre[k] = comm.sum(centre[k]);
    return centre;
}

std::string describe_counts(const std::vector<PatchFaces>& counts, std::size_t at_most = 4)
{
    std::string text;
    for (std::size_t k = 0; k < counts.size() && k < at_most; ++k)
        text += (k == 0                   ? ""
                 : k + 1 == counts.size() ? " and "
                                          : ", ") +
                counts[k].patch + " (" + std::to_string(counts[k].faces) +
                (counts[k].faces == 1 ? " face)" : " faces)");
    if (counts.size() > at_most)
        text += " and " + std::to_string(counts.size() - at_most) + " more";
    return text;
}

} // namespace

FoldedFaces faces_folded_by_prescription(const PolyMesh& mesh, const Constraints& c,
                                         const parallel::Communicator& comm)
{
    const FoldTest test{mesh, c, constraint_rows(mesh.n_points(), c)};
    std::vector<Index> turned;
    for (Index f : patch_faces(mesh))
        if (test.moved_whole(mesh.faces[f]) && test.turned_over(mesh.faces[f]))
            turned.push_back(f);
    std::vector<Index> faces;
    if (!turned.empty()) // the rare case: the addressing only then
    {
        const CompactList faces_of_point = point_faces(mesh);
        for (Index f : turned)
            if (test.folded_against_a_neighbour(f, faces_of_point))
                faces.push_back(f);
    }
    FoldedFaces out;
    out.faces = Index(comm.sum(std::int64_t(faces.size())));
    if (out.faces == 0)
        return out;
    std::vector<std::string> own;
    for (Index f : faces)
        own.push_back(patch_name_of(mesh, f));
    out.by_patch = count_by_name(mesh, own, comm);
    out.meeting = count_by_name(mesh, patches_met(mesh, faces), comm);
    out.example = example_centre(mesh, test, faces, comm);
    return out;
}

std::string describe(const FoldedFaces& folded)
{
    if (folded.faces == 0)
        return {};
    std::ostringstream text;
    text.precision(6);
    text << "the prescription itself folds " << folded.faces << " face"
         << (folded.faces == 1 ? "" : "s") << " over: " << describe_counts(folded.by_patch)
         << ", the one moved most at (" << folded.example.x() << " " << folded.example.y() << " "
         << folded.example.z()
         << "). Every point of them is prescribed, so no method, step or repair of the interior "
            "can unfold them (the boundary overlaps itself there)";
    if (!folded.meeting.empty())
        text << ". They meet " << describe_counts(folded.meeting)
             << ", where points held by another prescription or by the conflict rule sit beside "
                "points that move: change the prescription there";
    return text.str();
}

} // namespace meshmorph::morph
