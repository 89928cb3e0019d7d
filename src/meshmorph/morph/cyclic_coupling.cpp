// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/morph/cyclic_coupling.h"

#include <algorithm>
#include <map>
#include <sstream>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/patch_kinds.h"

namespace meshmorph::morph
{

namespace
{

//! The rotation that turns a vector of the neighbour side into this side's (forwardT).
Eigen::Matrix3d from_neighbour(const CyclicPatch& cp, Index face)
{
    if (cp.rotation.empty())
        return Eigen::Matrix3d::Identity();
    return cp.rotation[cp.rotation.size() == 1 ? 0 : static_cast<std::size_t>(face)];
}

//! The pairs of one owner-side cyclic: vertex j of face i meets vertex (n - j) % n of the
//! neighbour's face i.
void add_pairs(const PolyMesh& mesh, const CyclicPatch& cp, std::map<Index, CyclicPointPair>& out)
{
    const Patch& p = mesh.patches[static_cast<std::size_t>(cp.patch)];
    const Patch& nbr = mesh.patches[static_cast<std::size_t>(cp.neighbour)];
    for (Index i = 0; i < p.n_faces; ++i)
    {
        const std::span<const Index> face = mesh.faces[p.start_face + i];
        const std::span<const Index> other = mesh.faces[nbr.start_face + i];
        if (face.size() != other.size())
            throw InvalidInput("cyclic patches " + p.name + " and " + nbr.name + ": face " +
                               std::to_string(i) + " has " + std::to_string(face.size()) +
                               " points on one side and " + std::to_string(other.size()) +
                               " on the other");
        // R turns the partner's vectors into this side's; its transpose the other way.
        const Eigen::Matrix3d to_partner = from_neighbour(cp, i).transpose();
        const std::size_t n = face.size();
        for (std::size_t j = 0; j < n; ++j)
            out.emplace(face[j],
                        CyclicPointPair{face[j], other[(n - j) % n], to_partner, cp.patch});
    }
}

//! The prescription of point p in c (nullptr if none): c.points is sorted.
const Vector3* prescription(const Constraints& c, const std::vector<Vector3>& values, Index p)
{
    const auto it = std::lower_bound(c.points.begin(), c.points.end(), p);
    if (it == c.points.end() || *it != p)
        return nullptr;
    return &values[static_cast<std::size_t>(it - c.points.begin())];
}

std::string disagreement(const PolyMesh& mesh, const CyclicPointPair& pair, const Vector3& d,
                         const Vector3& partner)
{
    const auto v = [](const Vector3& x)
    {
        std::ostringstream s;
        s << '(' << x.x() << ' ' << x.y() << ' ' << x.z() << ')';
        return s.str();
    };
    return "cyclic patch " + mesh.patches[static_cast<std::size_t>(pair.patch)].name + ": point " +
           std::to_string(pair.point) + " is prescribed " + v(d) + " but its partner " +
           std::to_string(pair.partner) + " on the neighbour patch " + v(partner) +
           " (turned to this side): the two sides of a cyclic must move alike (give both the "
           "same motion, fix both, or leave one free so that it follows the other)";
}

//! Adds the prescriptions `added` (point, displacement; points not yet prescribed) to c,
//! keeping c.points sorted; an added point stops being a slip point.
void add_prescriptions(std::vector<std::pair<Index, Vector3>> added, Constraints& c,
                       std::vector<Vector3>& values)
{
    if (added.empty())
        return;
    std::sort(added.begin(), added.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    added.erase(std::unique(added.begin(), added.end(),
                            [](const auto& a, const auto& b) { return a.first == b.first; }),
                added.end());
    std::vector<Index> points;
    std::vector<Index> rotation_of;
    std::vector<Vector3> merged;
    std::size_t i = 0, k = 0;
    while (i < c.points.size() || k < added.size())
        if (k == added.size() || (i < c.points.size() && c.points[i] < added[k].first))
        {
            points.push_back(c.points[i]);
            rotation_of.push_back(c.rotation_of[i]);
            merged.push_back(values[i++]);
        }
        else
        {
            points.push_back(added[k].first);
            rotation_of.push_back(-1);
            merged.push_back(added[k++].second);
        }
    std::vector<Index> slip_points;
    std::vector<Eigen::Matrix3d> slip_projectors;
    for (std::size_t s = 0; s < c.slip_points.size(); ++s)
        if (!std::binary_search(points.begin(), points.end(), c.slip_points[s]))
        {
            slip_points.push_back(c.slip_points[s]);
            slip_projectors.push_back(c.slip_projectors[s]);
        }
    c.points = std::move(points);
    c.rotation_of = std::move(rotation_of);
    c.slip_points = std::move(slip_points);
    c.slip_projectors = std::move(slip_projectors);
    values = std::move(merged);
}

} // namespace

std::vector<CyclicPointPair> cyclic_point_pairs(const PolyMesh& mesh)
{
    bool has_cyclic = false;
    for (const Patch& p : mesh.patches)
    {
        if (is_processor_cyclic_patch(p) && p.n_faces > 0)
            throw InvalidInput("patch " + p.name +
                               " is a cyclic split across processors (processorCyclic): "
                               "decompose with the cyclic patches kept whole (decomposeParDict "
                               "preservePatches) so that each rank moves both sides alike");
        has_cyclic = has_cyclic || (is_coupled_patch(p) && p.n_faces > 0);
    }
    if (!has_cyclic)
        return {};
    const MeshGeometry g = compute_geometry(mesh, cell_faces(mesh));
    std::map<Index, CyclicPointPair> pairs; // one per owner-side point
    for (const CyclicPatch& cp : cyclic_patches(mesh, g))
        if (cp.owner())
            add_pairs(mesh, cp, pairs);
    std::vector<CyclicPointPair> out;
    for (const auto& [point, pair] : pairs)
        out.push_back(pair);
    return out;
}

void couple_cyclic_prescriptions(const PolyMesh& mesh, const std::vector<CyclicPointPair>& pairs,
                                 double tolerance, Constraints& c)
{
    std::vector<Vector3> values(c.points.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = c.displacements.row(static_cast<Eigen::Index>(i)).transpose();
    std::vector<CyclicPointPair> free_pairs;
    std::vector<std::pair<Index, Vector3>> added;
    for (const CyclicPointPair& pair : pairs)
    {
        const Vector3* d = prescription(c, values, pair.point);
        const Vector3* e = prescription(c, values, pair.partner);
        if (d && e)
        {
            const Vector3 turned = pair.to_partner.transpose() * *e;
            if ((turned - *d).norm() > tolerance)
                throw InvalidInput(disagreement(mesh, pair, *d, turned));
        }
        else if (d)
            added.emplace_back(pair.partner, pair.to_partner * *d);
        else if (e)
            added.emplace_back(pair.point, pair.to_partner.transpose() * *e);
        else
            free_pairs.push_back(pair);
    }
    add_prescriptions(std::move(added), c, values);
    c.displacements.resize(static_cast<Eigen::Index>(values.size()), 3);
    for (std::size_t i = 0; i < values.size(); ++i)
        c.displacements.row(static_cast<Eigen::Index>(i)) = values[i].transpose();
    c.cyclic_pairs = std::move(free_pairs);
}

void coupled_mean(const std::vector<CyclicPointPair>& pairs, Points& displacement)
{
    for (const CyclicPointPair& pair : pairs)
    {
        const Vector3 d = displacement.row(pair.point).transpose();
        const Vector3 e = pair.to_partner.transpose() * displacement.row(pair.partner).transpose();
        const Vector3 mean = 0.5 * (d + e);
        displacement.row(pair.point) = mean.transpose();
        displacement.row(pair.partner) = (pair.to_partner * mean).transpose();
    }
}

} // namespace meshmorph::morph
