// SPDX-License-Identifier: GPL-3.0-or-later
// The claims of boundary entries on their patches' points, one function per kind of motion.
#include "meshmorph/morph/claims.h"

#include <algorithm>
#include <map>
#include <stdexcept>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/mesh/patch_kinds.h"
#include "meshmorph/morph/patch_plane.h"

namespace meshmorph::morph
{

namespace
{

//! One patch and the entry that prescribes it.
struct PatchClaim
{
    const Patch& patch;
    Index index;               //!< patch index
    Index order;               //!< entry index (-1: implicit)
    Motion motion;             //!< of the entry (fixed when implicit)
    std::size_t line;          //!< of the entry, for messages
    std::string what;          //!< "boundary entry <key>", for messages
    std::vector<Index> points; //!< the patch's points
};

//! Surface points waiting for their projection, per target file.
struct SurfaceRequests
{
    std::vector<std::pair<std::size_t, Index>> claims; //!< (claim, point)
    std::string what;                                  //!< the first entry naming the file
    std::size_t line = 0;
};

using SurfaceQueue = std::map<std::string, SurfaceRequests>;

void add_claims(const PatchClaim& pc, Claim::Kind kind, const Vector3& value,
                std::vector<Claim>& claims)
{
    for (Index p : pc.points)
        claims.push_back({p, pc.index, pc.order, kind, value});
}

//! Slip and wedge patches: the point slides within the patch's plane.
void add_slip_claims(const PolyMesh& mesh, const MorphSetup& setup, const PatchClaim& pc,
                     std::vector<Claim>& claims)
{
    const auto plane = patch_plane(mesh, pc.patch);
    if (!plane && pc.patch.type == "wedge")
        throw InvalidInput("wedge patch '" + pc.patch.name + "' is not planar");
    if (!plane)
        throw ParseError(setup.dict_path, pc.line,
                         pc.what + ": patch '" + pc.patch.name +
                             "' is not planar, so type slip cannot keep its points on it (use "
                             "type surface with the patch's geometry instead)");
    add_claims(pc, Claim::Kind::slip, plane->first, claims);
}

//! The pointDisplacement field's values: the patch's own boundary values where given,
//! else the internal field at its points.
void add_point_displacement_claims(const PolyMesh& mesh, const MorphSetup& setup,
                                   const ConstraintInputs& inputs, const PatchClaim& pc,
                                   std::vector<Claim>& claims)
{
    if (inputs.point_displacement == nullptr)
        throw ParseError(setup.dict_path, pc.line,
                         pc.what + ": type pointDisplacement needs a pointDisplacement field, "
                                   "none was read");
    if (inputs.point_displacement->rows() != mesh.n_points())
        throw InvalidInput("pointDisplacement has " +
                           std::to_string(inputs.point_displacement->rows()) +
                           " values, the mesh has " + std::to_string(mesh.n_points()) + " points");
    const std::size_t pi = static_cast<std::size_t>(pc.index);
    const auto* per_patch = inputs.patch_point_displacement;
    if (per_patch != nullptr && pi < per_patch->size() && (*per_patch)[pi].has_value())
    {
        const Points& values = *(*per_patch)[pi];
        if (values.rows() != static_cast<Eigen::Index>(pc.points.size()))
            throw InvalidInput("pointDisplacement values of patch '" + pc.patch.name +
                               "' do not match its number of points");
        for (std::size_t i = 0; i < pc.points.size(); ++i)
            claims.push_back({pc.points[i], pc.index, pc.order, Claim::Kind::value,
                              values.row(static_cast<Eigen::Index>(i)).transpose()});
        return;
    }
    for (Index p : pc.points)
        claims.push_back({p, pc.index, pc.order, Claim::Kind::value,
                          inputs.point_displacement->row(p).transpose()});
}

//! Surface patches: value claims whose values project_surface_requests() fills in.
void add_surface_claims(const MorphSetup& setup, const ConstraintInputs& inputs,
                        const PatchClaim& pc, std::vector<Claim>& claims, SurfaceQueue& queue)
{
    if (!inputs.project_to_surface)
        throw ParseError(setup.dict_path, pc.line,
                         pc.what + ": type surface needs a target surface reader, none was "
                                   "given");
    auto [it, first] = queue.try_emplace(pc.motion.file);
    if (first)
    {
        it->second.what = pc.what;
        it->second.line = pc.line;
    }
    for (Index p : pc.points)
    {
        it->second.claims.emplace_back(claims.size(), p);
        claims.push_back({p, pc.index, pc.order, Claim::Kind::value, Vector3::Zero()});
    }
}

//! The index of `m` in rotations, appended on first use. Registered per boundary entry in
//! collect_claims (entry order), so that every rank of a -parallel run numbers them alike.
Index rotation_index(std::vector<Motion>& rotations, const Motion& m)
{
    for (std::size_t r = 0; r < rotations.size(); ++r)
        if (rotations[r].origin == m.origin && rotations[r].axis == m.axis &&
            rotations[r].angle_degrees == m.angle_degrees)
            return static_cast<Index>(r);
    rotations.push_back(m);
    return static_cast<Index>(rotations.size() - 1);
}

//! fixed, translate, rotate, scale. 2D: evaluated at the projection onto the reference
//! empty plane, so both planes get the same prescription (a rotation about a tilted axis
//! would otherwise differ between them).
void add_closed_form_claims(const PolyMesh& mesh, const std::optional<EmptyPlanes>& planes,
                            const PatchClaim& pc, std::vector<Claim>& claims,
                            std::vector<Motion>& rotations)
{
    Index rotation = -1;
    if (pc.motion.type == MotionType::rotate)
        rotation = rotation_index(rotations, pc.motion);
    for (Index p : pc.points)
    {
        const Vector3 x = evaluation_position(planes, mesh.points.row(p).transpose());
        claims.push_back(
            {p, pc.index, pc.order, Claim::Kind::value, pc.motion.displacement(x), rotation});
    }
}

//! A target much farther from its points than their own extent is most likely the wrong
//! file, units or position: the morph goes on (large motions are legitimate) but says so.
void warn_if_far(const MorphSetup& setup, const SurfaceRequests& requests, const std::string& file,
                 const Points& query, const Points& closest)
{
    if (query.rows() == 0)
        return;
    const double extent = (query.colwise().maxCoeff() - query.colwise().minCoeff()).norm();
    const double distance = (closest - query).rowwise().norm().maxCoeff();
    if (extent > 0 && distance > extent)
        log::warning() << setup.dict_path << ":" << requests.line << ": " << requests.what
                       << ": the surface \"" << file
                       << "\" is far from its points: they move up to " << distance
                       << ", more than their own extent " << extent
                       << " (is it the right surface, in the right units and position?)";
}

//! Project every queued surface point onto its target, one query per file.
void project_surface_requests(const PolyMesh& mesh, const MorphSetup& setup,
                              const ConstraintInputs& inputs, const SurfaceQueue& queue,
                              std::vector<Claim>& claims)
{
    for (const auto& [file, requests] : queue)
    {
        Points query(static_cast<Eigen::Index>(requests.claims.size()), 3);
        for (std::size_t i = 0; i < requests.claims.size(); ++i)
            query.row(static_cast<Eigen::Index>(i)) = mesh.points.row(requests.claims[i].second);
        Points closest;
        try
        {
            closest = inputs.project_to_surface(file, query);
        }
        catch (const Error& e)
        {
            // Name the dictionary entry as well as the surface file.
            throw ParseError(setup.dict_path, requests.line,
                             requests.what + ": cannot use surface \"" + file + "\": " + e.what());
        }
        if (closest.rows() != query.rows())
            throw std::logic_error("project_to_surface returned a wrong number of points");
        for (std::size_t i = 0; i < requests.claims.size(); ++i)
        {
            const Eigen::Index r = static_cast<Eigen::Index>(i);
            claims[requests.claims[i].first].value = (closest.row(r) - query.row(r)).transpose();
        }
        warn_if_far(setup, requests, file, query, closest);
    }
}

PatchClaim patch_claim(const PolyMesh& mesh, const MorphSetup& setup, std::size_t pi,
                       const PatchAssignment& a)
{
    const bool explicit_entry = a.entry >= 0;
    const BoundaryEntry* entry = explicit_entry ? &setup.boundary[a.entry] : nullptr;
    return {mesh.patches[pi],
            static_cast<Index>(pi),
            a.entry,
            entry != nullptr ? entry->motion : Motion{},
            entry != nullptr ? entry->line : 0,
            entry != nullptr
                ? "boundary entry " + (entry->is_regex ? "\"" + entry->key + "\"" : entry->key)
                : std::string(),
            patch_points(mesh, mesh.patches[pi])};
}

} // namespace

std::vector<Claim> collect_claims(const PolyMesh& mesh, const MorphSetup& setup,
                                  const std::vector<PatchAssignment>& patches,
                                  const ConstraintInputs& inputs,
                                  const std::optional<EmptyPlanes>& planes,
                                  std::vector<Motion>& rotations)
{
    std::vector<Claim> claims;
    SurfaceQueue surfaces;
    for (const BoundaryEntry& e : setup.boundary)
        if (e.motion.type == MotionType::rotate)
            rotation_index(rotations, e.motion);
    for (std::size_t pi = 0; pi < mesh.patches.size(); ++pi)
    {
        const Patch& patch = mesh.patches[pi];
        if (patch.type == "empty" || is_processor_patch(patch) || patch.n_faces == 0)
            continue;
        const PatchClaim pc = patch_claim(mesh, setup, pi, patches[pi]);
        if (patch.type == "wedge" || pc.motion.type == MotionType::slip)
            add_slip_claims(mesh, setup, pc, claims);
        else if (pc.motion.type == MotionType::free)
            add_claims(pc, Claim::Kind::free, Vector3::Zero(), claims);
        else if (pc.motion.type == MotionType::point_displacement)
            add_point_displacement_claims(mesh, setup, inputs, pc, claims);
        else if (pc.motion.type == MotionType::surface)
            add_surface_claims(setup, inputs, pc, claims, surfaces);
        else
            add_closed_form_claims(mesh, planes, pc, claims, rotations);
    }
    project_surface_requests(mesh, setup, inputs, surfaces, claims);
    std::stable_sort(claims.begin(), claims.end(),
                     [](const Claim& a, const Claim& b) { return a.point < b.point; });
    return claims;
}

} // namespace meshmorph::morph
