// SPDX-License-Identifier: GPL-3.0-or-later
// Handle selections (pointZone, box, nearest points) and their claims.
#include "meshmorph/morph/handle_selection.h"

#include <algorithm>
#include <limits>

#include "meshmorph/core/exceptions.h"

namespace meshmorph::morph
{

namespace
{

std::vector<Index> zone_points(const PolyMesh& mesh, const HandleEntry& handle,
                               const std::string& dict_path)
{
    auto it = std::find_if(mesh.point_zones.begin(), mesh.point_zones.end(),
                           [&](const Zone& z) { return z.name == handle.zone; });
    if (it != mesh.point_zones.end())
        return it->labels;
    std::string zones;
    for (const Zone& z : mesh.point_zones)
        zones += (zones.empty() ? "" : " ") + z.name;
    throw ParseError(dict_path, handle.line,
                     "handles entry '" + handle.name + "': no pointZone '" + handle.zone +
                         "' in the mesh (pointZones: " + (zones.empty() ? "none" : zones) + ")");
}

std::vector<Index> box_points(const PolyMesh& mesh, const HandleEntry& handle)
{
    std::vector<Index> selected;
    for (Index p = 0; p < mesh.n_points(); ++p)
    {
        const Vector3 x = mesh.points.row(p).transpose();
        if ((x.array() >= handle.box_min.array()).all() &&
            (x.array() <= handle.box_max.array()).all())
            selected.push_back(p);
    }
    return selected;
}

bool distributed(const Decomposition* d)
{
    return d != nullptr && d->is_distributed();
}

//! The lowest global label among this rank's points at `distance`, over every rank.
Index lowest_label_at(const Eigen::VectorXd& dist, double distance, const Decomposition& d)
{
    std::int64_t mine = std::numeric_limits<std::int64_t>::max();
    for (Index p = 0; p < dist.size(); ++p)
        if (dist[p] == distance)
            mine = std::min<std::int64_t>(mine, d.global_point[std::size_t(p)]);
    return static_cast<Index>(-d.comm->max(-mine));
}

//! The mesh point nearest to x (the lowest label among equally near ones); in a 2D case every
//! point within `tolerance` of the nearest distance in the plane of the case (one per empty
//! plane). Decomposed: the nearest over every rank, selected where it lies.
std::vector<Index> nearest_points(const PolyMesh& mesh, const Vector3& x,
                                  const std::optional<EmptyPlanes>& planes, double tolerance,
                                  const Decomposition* decomposition)
{
    Points d = mesh.points.rowwise() - x.transpose();
    if (planes)
        planes->remove_normal(d);
    const Eigen::VectorXd dist = d.rowwise().norm();
    Eigen::Index nearest = 0;
    double closest =
        dist.size() > 0 ? dist.minCoeff(&nearest) : std::numeric_limits<double>::infinity();
    if (distributed(decomposition))
        closest = decomposition->comm->min(closest);
    std::vector<Index> out;
    if (planes)
    {
        for (Index p = 0; p < mesh.n_points(); ++p)
            if (dist[p] <= closest + tolerance)
                out.push_back(p);
        return out;
    }
    if (!distributed(decomposition))
        return {static_cast<Index>(nearest)};
    const Index label = lowest_label_at(dist, closest, *decomposition);
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (decomposition->global_point[std::size_t(p)] == label)
            out.push_back(p);
    return out;
}

std::vector<Index> nearest_to_positions(const PolyMesh& mesh, const HandleEntry& handle,
                                        const std::optional<EmptyPlanes>& planes, double tolerance,
                                        const Decomposition* decomposition)
{
    std::vector<Index> selected;
    for (Eigen::Index k = 0; k < handle.points.rows(); ++k)
        for (Index p : nearest_points(mesh, handle.points.row(k).transpose(), planes, tolerance,
                                      decomposition))
            selected.push_back(p);
    return selected;
}

} // namespace

std::vector<Index> select_handle_points(const PolyMesh& mesh, const HandleEntry& handle,
                                        const std::optional<EmptyPlanes>& planes, double tolerance,
                                        const std::string& dict_path,
                                        const Decomposition* decomposition)
{
    std::vector<Index> selected;
    switch (handle.selection)
    {
    case HandleEntry::Selection::point_zone:
        selected = zone_points(mesh, handle, dict_path);
        break;
    case HandleEntry::Selection::box:
        selected = box_points(mesh, handle);
        break;
    case HandleEntry::Selection::points:
        selected = nearest_to_positions(mesh, handle, planes, tolerance, decomposition);
        break;
    case HandleEntry::Selection::labels:
        selected = handle.labels;
        break;
    }
    const bool none = distributed(decomposition)
                          ? decomposition->comm->sum(std::int64_t(selected.size())) == 0
                          : selected.empty();
    if (none)
        throw ParseError(dict_path, handle.line,
                         "handles entry '" + handle.name + "' selects no mesh point");
    for (Index p : selected)
        if (p < 0 || p >= mesh.n_points())
            throw InvalidInput((handle.selection == HandleEntry::Selection::labels
                                    ? "point set '" + handle.name + "'"
                                    : "pointZone '" + handle.zone + "'") +
                               " has point label " + std::to_string(p) + " out of range (" +
                               std::to_string(mesh.n_points()) + " points)");
    return selected;
}

namespace
{

//! The handle's displacement at x (evaluated on the reference empty plane in 2D cases,
//! as the boundary's closed-form motions are; a normal part is refused by
//! check_prescriptions, not dropped).
Vector3 handle_displacement(const HandleEntry& handle, const Vector3& x,
                            const std::optional<EmptyPlanes>& planes)
{
    if (!handle.displacement_at)
        return handle.displacement;
    return handle.displacement_at(planes ? planes->project(x) : x);
}

//! A labels selection's k-th displacement.
Vector3 listed_displacement(const HandleEntry& handle, std::size_t k)
{
    return handle.label_displacements.row(static_cast<Eigen::Index>(k)).transpose();
}

} // namespace

std::vector<Claim> collect_handle_claims(const PolyMesh& mesh, const MorphSetup& setup,
                                         const std::optional<EmptyPlanes>& planes, double tolerance,
                                         const Decomposition* decomposition)
{
    std::vector<Claim> claims;
    for (std::size_t h = 0; h < setup.handles.size(); ++h)
    {
        const HandleEntry& handle = setup.handles[h];
        const Index source = static_cast<Index>(h);
        const std::vector<Index> selected =
            select_handle_points(mesh, handle, planes, tolerance, setup.dict_path, decomposition);
        for (std::size_t k = 0; k < selected.size(); ++k)
        {
            const Index p = selected[k];
            const Vector3 d =
                handle.selection == HandleEntry::Selection::labels
                    ? listed_displacement(handle, k)
                    : handle_displacement(handle, mesh.points.row(p).transpose(), planes);
            claims.push_back({p, source, source, Claim::Kind::value, d});
        }
    }
    std::stable_sort(claims.begin(), claims.end(),
                     [](const Claim& a, const Claim& b) { return a.point < b.point; });
    const auto same = [](const Claim& a, const Claim& b)
    { return a.point == b.point && a.source == b.source; };
    claims.erase(std::unique(claims.begin(), claims.end(), same), claims.end());
    return claims;
}

} // namespace meshmorph::morph
