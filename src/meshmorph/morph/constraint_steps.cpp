// SPDX-License-Identifier: GPL-3.0-or-later
// The steps of build_constraints, shared by the serial and the distributed composition.
#include "meshmorph/morph/constraint_steps.h"
#include "meshmorph/morph/prescription_checks.h"

#include <algorithm>
#include <limits>
#include <set>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/mesh/patch_kinds.h"

namespace meshmorph::morph::detail
{

namespace
{

// Prescriptions of a point that differ by at most this fraction of its shortest boundary
// edge agree "to the mesh's resolution" (conflict_resolution.h).
constexpr double near_agreement_fraction = 0.1;

//! "inlet/wall": the patches of the claims, sorted and joined.
std::string patch_conflict_name(const PolyMesh& mesh, const std::vector<const Claim*>& claims)
{
    std::set<std::string> names;
    for (const Claim* c : claims)
        names.insert(mesh.patches[c->source].name);
    std::string key;
    for (const std::string& n : names)
        key += (key.empty() ? "" : "/") + n;
    return key;
}

//! "handles lift push": the handles of the claims, in dictionary order.
std::string handle_conflict_name(const MorphSetup& setup, const std::vector<const Claim*>& claims)
{
    std::string key = "handles";
    for (const Claim* c : claims)
        key += " " + setup.handles[c->source].name;
    return key;
}

std::string indented(const std::vector<std::string>& lines)
{
    std::string list;
    for (const std::string& line : lines)
        list += "\n    " + line;
    return list;
}

void append_value(const Resolved& r, std::vector<Vector3>& values, Constraints& out)
{
    out.points.push_back(r.point);
    values.push_back(r.value);
    out.rotation_of.push_back(r.rotation);
}

} // namespace

//! Two prescriptions agree when they differ by less than this: far below any motion
//! meaningful for a mesh, far above round-off of the closed-form motions.
double agreement_tolerance(const Vector3& lo, const Vector3& hi)
{
    return 1e-12 * std::max((hi - lo).norm(), constants::vsmall);
}

std::vector<double> shortest_boundary_edges(const PolyMesh& mesh)
{
    std::vector<double> shortest(static_cast<std::size_t>(mesh.n_points()),
                                 std::numeric_limits<double>::infinity());
    for (const Patch& patch : mesh.patches)
    {
        if (is_processor_patch(patch))
            continue;
        for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
        {
            const std::span<const Index> face = mesh.faces[f];
            for (std::size_t i = 0; i < face.size(); ++i)
            {
                const Index a = face[i], b = face[(i + 1) % face.size()];
                const double l = (mesh.points.row(a) - mesh.points.row(b)).norm();
                for (Index p : {a, b})
                    shortest[static_cast<std::size_t>(p)] =
                        std::min(shortest[static_cast<std::size_t>(p)], l);
            }
        }
    }
    return shortest;
}

Resolution resolve_boundary(const PolyMesh& mesh, const MorphSetup& setup,
                            const std::vector<Claim>& claims, const std::vector<double>& edges,
                            double agree_tol, Constraints& out)
{
    ResolveSettings s;
    s.rule = setup.conflicts;
    s.agree_tolerance = agree_tol;
    s.in_plane_tolerance = in_plane_fraction;
    s.shortest_edges = &edges;
    s.near_agreement = near_agreement_fraction;
    s.conflict_name = [&](const std::vector<const Claim*>& c)
    { return patch_conflict_name(mesh, c); };
    Resolution r = resolve(claims, s);
    out.n_free_points = r.n_free;
    out.n_conflicts = r.n_conflicts;
    out.n_near_agreements = r.n_near_agreements;
    out.max_near_agreement = r.max_near_agreement;
    out.conflict_summary = r.conflict_summary();
    if (out.n_conflicts > 0 && setup.conflicts == ConflictRule::error)
        throw InvalidInput(setup.dict_path + ": " + std::to_string(out.n_conflicts) +
                           " points lie on patches with different prescriptions (conflicts "
                           "error):" +
                           indented(out.conflict_summary) +
                           "\n  set 'conflicts' to fixed, first, last or average to resolve them");
    return r;
}

Resolution resolve_handles(const MorphSetup& setup, const std::vector<Claim>& claims,
                           double agree_tol, Constraints& out)
{
    ResolveSettings s;
    s.rule = setup.conflicts;
    s.agree_tolerance = agree_tol;
    s.conflict_name = [&](const std::vector<const Claim*>& c)
    { return handle_conflict_name(setup, c); };
    Resolution r = resolve(claims, s);
    out.n_conflicts += r.n_conflicts;
    const std::vector<std::string> summary = r.conflict_summary();
    out.conflict_summary.insert(out.conflict_summary.end(), summary.begin(), summary.end());
    if (!r.conflicts.empty() && setup.conflicts == ConflictRule::error)
        throw InvalidInput(
            setup.dict_path + ": overlapping handles prescribe different displacements (" +
            r.conflicts.begin()->first + "); set 'conflicts' to fixed, first, last or average");
    out.n_handle_points = static_cast<Index>(r.points.size());
    return r;
}

std::vector<Vector3> merge(const std::vector<Resolved>& boundary,
                           const std::vector<Resolved>& handles, Constraints& out)
{
    std::vector<Vector3> values;
    auto h = handles.begin();
    for (const Resolved& r : boundary)
    {
        for (; h != handles.end() && h->point < r.point; ++h)
            append_value(*h, values, out);
        if (h != handles.end() && h->point == r.point)
        {
            ++out.n_handle_overrides;
            append_value(*h++, values, out);
        }
        else if (r.is_slip)
        {
            out.slip_points.push_back(r.point);
            out.slip_projectors.push_back(r.projector);
        }
        else
            append_value(r, values, out);
    }
    for (; h != handles.end(); ++h)
        append_value(*h, values, out);
    return values;
}

bool any_motion(const std::vector<Claim>& claims, double tolerance)
{
    return std::any_of(claims.begin(), claims.end(),
                       [&](const Claim& c)
                       { return c.kind == Claim::Kind::value && c.value.norm() > tolerance; });
}

void require_some_motion(const MorphSetup& setup, bool asked, const std::vector<Vector3>& values,
                         const Constraints& out, double tolerance)
{
    const bool moves = std::any_of(values.begin(), values.end(),
                                   [&](const Vector3& v) { return v.norm() > tolerance; });
    if (!asked || moves)
        return;
    const std::string list = indented(out.conflict_summary);
    throw InvalidInput(setup.dict_path +
                       ": the dictionary asks for motion but every prescribed displacement "
                       "resolves to zero, so nothing would move" +
                       (list.empty()
                            ? std::string(".")
                            : " (conflicts resolved by rule '" + to_string(setup.conflicts) +
                                  "':" + list + "\n  set 'conflicts' to first, last or average)"));
}

std::vector<Vector3> resolve_and_merge(const PolyMesh& mesh, const MorphSetup& setup,
                                       const std::vector<Claim>& claims,
                                       const std::vector<double>& edges,
                                       const std::vector<Claim>& handle_claims, double agree_tol,
                                       double diagonal, Constraints& out)
{
    check_prescriptions(mesh, setup, claims, handle_claims, out.empty_planes, diagonal, agree_tol);
    const Resolution boundary = resolve_boundary(mesh, setup, claims, edges, agree_tol, out);
    const Resolution handles = resolve_handles(setup, handle_claims, agree_tol, out);
    const std::vector<Vector3> values = merge(boundary.points, handles.points, out);
    require_some_motion(setup,
                        any_motion(claims, agree_tol) || any_motion(handle_claims, agree_tol),
                        values, out, agree_tol);
    return values;
}

void fill_displacements(const std::vector<Vector3>& values, Constraints& out)
{
    out.n_prescribed_points = static_cast<Index>(out.points.size());
    out.n_slip_points = static_cast<Index>(out.slip_points.size());
    out.displacements.resize(static_cast<Eigen::Index>(values.size()), 3);
    for (std::size_t i = 0; i < values.size(); ++i)
        out.displacements.row(static_cast<Eigen::Index>(i)) =
            in_plane(out.empty_planes, values[i]).transpose();
}

} // namespace meshmorph::morph::detail
