// SPDX-License-Identifier: GPL-3.0-or-later
// Boundary/handle prescriptions of morphDict resolved into point constraints.
#include "meshmorph/app/morph_setup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/foam_dictionary.h"

namespace meshmorph::app
{

namespace
{

const std::vector<std::pair<MotionType, std::string>>& motion_names()
{
    static const std::vector<std::pair<MotionType, std::string>> names{
        {MotionType::fixed, "fixed"},
        {MotionType::translate, "translate"},
        {MotionType::rotate, "rotate"},
        {MotionType::scale, "scale"},
        {MotionType::point_displacement, "pointDisplacement"},
        {MotionType::surface, "surface"},
        {MotionType::slip, "slip"},
        {MotionType::free, "free"}};
    return names;
}

const std::vector<std::pair<ConflictRule, std::string>>& rule_names()
{
    static const std::vector<std::pair<ConflictRule, std::string>> names{
        {ConflictRule::error, "error"},
        {ConflictRule::first, "first"},
        {ConflictRule::last, "last"},
        {ConflictRule::fixed, "fixed"},
        {ConflictRule::average, "average"}};
    return names;
}

bool is_constraint_type(const std::string& type)
{
    return type == "empty" || type == "wedge";
}

bool is_processor_type(const std::string& type)
{
    return type == "processor" || type == "processorCyclic";
}

//! Patch groups a key may name: inGroups plus the patch type for constraint-like types
//! (OpenFOAM adds wall, empty, wedge, symmetryPlane, ... automatically).
std::vector<std::string> patch_groups(const Patch& patch)
{
    std::vector<std::string> groups = patch.in_groups;
    if (patch.type != "patch" &&
        std::find(groups.begin(), groups.end(), patch.type) == groups.end())
        groups.push_back(patch.type);
    return groups;
}

std::string entry_label(const BoundaryEntry& e)
{
    return e.is_regex ? "\"" + e.key + "\"" : e.key;
}

//! Area vector of a face (Newell's formula: exact for planar polygons, the mean plane's
//! normal times area for warped ones).
Vector3 face_area_vector(const PolyMesh& mesh, std::span<const Index> face)
{
    Vector3 a = Vector3::Zero();
    const std::size_t n = face.size();
    for (std::size_t i = 0; i < n; ++i)
    {
        const Vector3 p = mesh.points.row(face[i]).transpose();
        const Vector3 q = mesh.points.row(face[(i + 1) % n]).transpose();
        a += p.cross(q);
    }
    return 0.5 * a;
}

double mesh_diagonal(const PolyMesh& mesh)
{
    if (mesh.n_points() == 0)
        return 1.0;
    const Vector3 lo = mesh.points.colwise().minCoeff().transpose();
    const Vector3 hi = mesh.points.colwise().maxCoeff().transpose();
    return std::max((hi - lo).norm(), constants::vsmall);
}

//! One prescription claiming one point.
struct Claim
{
    enum class Kind : char
    {
        value,
        slip,
        free
    };
    Index point = 0;
    Index patch = 0;
    Index order = 0; //!< entry order in the dictionary (wedge: -1)
    Kind kind = Kind::value;
    Vector3 value = Vector3::Zero(); //!< value: displacement; slip: plane normal
    Index rotation = -1; //!< value claimed by a rotate entry: index into Constraints::rotations
};

//! Projector removing the components along the given unit normals (an orthonormal basis of
//! their span is built first, so two nearly equal normals count once).
Eigen::Matrix3d slip_projector(const std::vector<Vector3>& normals, int& rank)
{
    std::vector<Vector3> basis;
    for (const Vector3& n : normals)
    {
        Vector3 v = n;
        for (const Vector3& b : basis)
            v -= v.dot(b) * b;
        // Planes within ~0.06 degrees of each other are the same plane here.
        if (v.norm() > 1e-3)
            basis.push_back(v.normalized());
    }
    rank = static_cast<int>(basis.size());
    Eigen::Matrix3d P = Eigen::Matrix3d::Identity();
    for (const Vector3& b : basis)
        P -= b * b.transpose();
    return P;
}

//! Keywords a boundary entry of each type may have (besides `type`).
std::vector<std::string> motion_keywords(MotionType type)
{
    switch (type)
    {
    case MotionType::translate:
        return {"vector"};
    case MotionType::rotate:
        return {"origin", "axis", "angle"};
    case MotionType::scale:
        return {"origin", "factor"};
    case MotionType::surface:
        return {"file"};
    default:
        return {};
    }
}

//! `box (x0 y0 z0) (x1 y1 z1);` or `box ((x0 y0 z0) (x1 y1 z1));`
std::pair<Vector3, Vector3> read_box(const io::FoamEntry& e)
{
    const std::vector<io::FoamValueToken>& t = e.tokens();
    if (t.size() == 10 && t[0].is_punct('(') && t[5].is_punct('('))
    {
        std::array<Vector3, 2> corners;
        for (int c = 0; c < 2; ++c)
        {
            const std::size_t base = 5 * static_cast<std::size_t>(c);
            if (!t[base + 4].is_punct(')'))
                throw e.error("expected two corners (x0 y0 z0) (x1 y1 z1)");
            for (int a = 0; a < 3; ++a)
            {
                if (!t[base + 1 + a].is_number())
                    throw e.error("expected a number, found " + t[base + 1 + a].describe());
                corners[c][a] = t[base + 1 + a].scalar;
            }
        }
        return {corners[0], corners[1]};
    }
    const std::vector<Vector3> corners = e.get<std::vector<Vector3>>();
    if (corners.size() != 2)
        throw e.error("expected two corners (x0 y0 z0) (x1 y1 z1)");
    return {corners[0], corners[1]};
}

} // namespace

MorphSetup read_morph_setup(const io::FoamDictionary& dict)
{
    MorphSetup setup;
    setup.dict_path = dict.path();
    // Other top-level entries are allowed when used as $variables (helper entries).
    dict.check_keywords({"method", "rbf", "dmffd", "ffd", "idw", "steps", "untangle", "boundary",
                         "handles", "conflicts"},
                        "morphDict", dict.referenced_variables());
    if (const io::FoamEntry* e = dict.find("conflicts"))
    {
        try
        {
            setup.conflicts = conflict_rule_from_string(e->get<std::string>());
        }
        catch (const InvalidInput& err)
        {
            throw e->error(err.what());
        }
    }

    if (dict.found("boundary"))
    {
        const io::FoamDictionary& boundary = dict.sub_dict("boundary");
        for (const io::FoamEntry& e : boundary.entries())
        {
            if (!e.is_dict())
                throw e.error("expected a sub-dictionary { type <fixed|translate|...>; ... }");
            const io::FoamDictionary& d = e.dict();
            BoundaryEntry entry;
            entry.key = e.keyword();
            entry.is_regex = e.is_regex();
            entry.line = e.line();
            const io::FoamEntry& type_entry = d.entry("type");
            const std::string type = type_entry.get<std::string>();
            if (type == "empty" || type == "wedge")
                throw type_entry.error("type " + type +
                                       " is implied by the patch type; remove the entry");
            try
            {
                entry.motion.type = motion_type_from_string(type);
            }
            catch (const InvalidInput& err)
            {
                throw type_entry.error(err.what());
            }
            std::vector<std::string> allowed = motion_keywords(entry.motion.type);
            allowed.push_back("type");
            d.check_keywords(allowed, "type " + type);
            Motion& m = entry.motion;
            switch (m.type)
            {
            case MotionType::translate:
                m.vector = d.get<Vector3>("vector");
                break;
            case MotionType::rotate:
                m.origin = d.get<Vector3>("origin");
                m.axis = d.get<Vector3>("axis");
                m.angle_degrees = d.get<double>("angle");
                if (m.axis.norm() == 0.0)
                    throw d.entry("axis").error("rotation axis must not be zero");
                break;
            case MotionType::scale:
            {
                m.origin = d.get<Vector3>("origin");
                const io::FoamEntry& f = d.entry("factor");
                if (f.tokens().size() == 1)
                    m.factor = Vector3::Constant(f.get<double>());
                else
                    m.factor = f.get<Vector3>();
                break;
            }
            case MotionType::surface:
                m.file = d.get<std::string>("file");
                break;
            default:
                break;
            }
            if (!m.vector.allFinite() || !m.origin.allFinite() || !m.axis.allFinite() ||
                !m.factor.allFinite() || !std::isfinite(m.angle_degrees))
                throw e.error("non-finite value");
            setup.boundary.push_back(std::move(entry));
        }
    }

    if (dict.found("handles"))
    {
        const io::FoamDictionary& handles = dict.sub_dict("handles");
        for (const io::FoamEntry& e : handles.entries())
        {
            if (!e.is_dict())
                throw e.error("expected a sub-dictionary { pointZone <name> | box (x0 y0 z0) "
                              "(x1 y1 z1) | points (...); displacement (dx dy dz); }");
            const io::FoamDictionary& d = e.dict();
            d.check_keywords({"pointZone", "box", "points", "displacement"}, "a handle");
            HandleEntry h;
            h.name = e.keyword();
            h.line = e.line();
            h.displacement = d.get<Vector3>("displacement");
            const int n_selections =
                int(d.found("pointZone")) + int(d.found("box")) + int(d.found("points"));
            if (n_selections != 1)
                throw e.error("give exactly one of pointZone, box or points");
            if (d.found("pointZone"))
            {
                h.selection = HandleEntry::Selection::point_zone;
                h.zone = d.get<std::string>("pointZone");
            }
            else if (d.found("box"))
            {
                h.selection = HandleEntry::Selection::box;
                std::tie(h.box_min, h.box_max) = read_box(d.entry("box"));
                if ((h.box_min.array() > h.box_max.array()).any())
                    throw d.entry("box").error("box min corner exceeds max corner");
            }
            else
            {
                h.selection = HandleEntry::Selection::points;
                const std::vector<Vector3> pts = d.get<std::vector<Vector3>>("points");
                if (pts.empty())
                    throw d.entry("points").error("empty list");
                h.points.resize(static_cast<Eigen::Index>(pts.size()), 3);
                for (std::size_t i = 0; i < pts.size(); ++i)
                    h.points.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
            }
            setup.handles.push_back(std::move(h));
        }
    }
    return setup;
}

std::string to_string(MotionType type)
{
    for (const auto& [t, name] : motion_names())
        if (t == type)
            return name;
    return "?";
}

MotionType motion_type_from_string(const std::string& word)
{
    std::string valid;
    for (const auto& [t, name] : motion_names())
    {
        if (name == word)
            return t;
        valid += (valid.empty() ? "" : " ") + name;
    }
    throw InvalidInput("unknown type '" + word + "' (valid types: " + valid + ")");
}

std::string to_string(ConflictRule rule)
{
    for (const auto& [r, name] : rule_names())
        if (r == rule)
            return name;
    return "?";
}

ConflictRule conflict_rule_from_string(const std::string& word)
{
    std::string valid;
    for (const auto& [r, name] : rule_names())
    {
        if (name == word)
            return r;
        valid += (valid.empty() ? "" : " ") + name;
    }
    throw InvalidInput("unknown conflict rule '" + word + "' (valid: " + valid + ")");
}

Vector3 Motion::displacement(const Vector3& x) const
{
    switch (type)
    {
    case MotionType::fixed:
        return Vector3::Zero();
    case MotionType::translate:
        return vector;
    case MotionType::rotate:
    {
        const double angle = angle_degrees * std::numbers::pi / 180.0;
        const Eigen::AngleAxisd rotation(angle, axis.normalized());
        return (rotation * (x - origin) + origin - x).eval();
    }
    case MotionType::scale:
        return (origin + factor.cwiseProduct(x - origin) - x).eval();
    default:
        throw std::logic_error("Motion::displacement: not a closed-form type");
    }
}

std::optional<std::pair<Vector3, double>> patch_plane(const PolyMesh& mesh, const Patch& patch,
                                                      double tolerance)
{
    if (patch.n_faces == 0)
        return std::nullopt;
    Vector3 area = Vector3::Zero();
    double total_area = 0.0;
    for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
    {
        const Vector3 a = face_area_vector(mesh, mesh.faces[f]);
        area += a;
        total_area += a.norm();
    }
    // A closed or strongly curved patch has a small net area vector: no plane.
    if (area.norm() < 0.5 * total_area || area.norm() <= constants::vsmall)
        return std::nullopt;
    const Vector3 n = area.normalized();
    const std::vector<Index> pts = patch_points(mesh, patch);
    Vector3 lo = Vector3::Constant(constants::vgreat);
    Vector3 hi = Vector3::Constant(-constants::vgreat);
    Vector3 centre = Vector3::Zero();
    for (Index p : pts)
    {
        const Vector3 x = mesh.points.row(p).transpose();
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
        centre += x;
    }
    centre /= static_cast<double>(pts.size());
    const double offset = n.dot(centre);
    double deviation = 0.0;
    for (Index p : pts)
        deviation = std::max(deviation, std::abs(n.dot(mesh.points.row(p).transpose()) - offset));
    if (deviation > tolerance * (hi - lo).norm())
        return std::nullopt;
    return std::make_pair(n, offset);
}

std::vector<PatchAssignment> assign_patches(const PolyMesh& mesh, const MorphSetup& setup)
{
    const std::string& dict = setup.dict_path;

    // Compile regexes once; a bad regex is a dictionary error.
    std::vector<std::optional<std::regex>> regexes(setup.boundary.size());
    Index default_entry = -1;
    for (std::size_t e = 0; e < setup.boundary.size(); ++e)
    {
        const BoundaryEntry& entry = setup.boundary[e];
        if (entry.is_regex)
        {
            try
            {
                regexes[e].emplace(entry.key, std::regex::ECMAScript);
            }
            catch (const std::regex_error& err)
            {
                throw ParseError(dict, entry.line,
                                 "boundary entry \"" + entry.key +
                                     "\": invalid regular expression (" + err.what() + ")");
            }
        }
        else if (entry.key == "default")
            default_entry = static_cast<Index>(e);
    }

    std::vector<char> entry_used(setup.boundary.size(), 0);
    std::vector<PatchAssignment> result;
    result.reserve(mesh.patches.size());
    for (const Patch& patch : mesh.patches)
    {
        if (is_processor_type(patch.type))
            throw InvalidInput("patch '" + patch.name + "' is of type " + patch.type +
                               ": decomposed/processor patches not supported yet "
                               "(run morphMesh on the reconstructed case)");
        const std::vector<std::string> groups = patch_groups(patch);
        Index by_name = -1;
        Index by_group = -1;
        Index by_regex = -1;
        std::string group_name;
        for (std::size_t e = 0; e < setup.boundary.size(); ++e)
        {
            const BoundaryEntry& entry = setup.boundary[e];
            if (entry.is_regex)
            {
                if (std::regex_match(patch.name, *regexes[e]))
                {
                    by_regex = static_cast<Index>(e); // the last one written wins
                    entry_used[e] = 1;
                }
            }
            else if (entry.key == patch.name)
            {
                by_name = static_cast<Index>(e);
                entry_used[e] = 1;
            }
            else if (std::find(groups.begin(), groups.end(), entry.key) != groups.end())
            {
                by_group = static_cast<Index>(e); // entries later in the file win
                group_name = entry.key;
                entry_used[e] = 1;
            }
        }

        PatchAssignment a;
        a.patch = patch.name;
        a.patch_type = patch.type;
        a.n_points = static_cast<Index>(patch_points(mesh, patch).size());
        if (is_constraint_type(patch.type))
        {
            // Explicitly naming a constraint patch (by name or group) with a motion would
            // change its OpenFOAM meaning; regex and default entries simply skip it.
            const Index explicit_entry = by_name >= 0 ? by_name : by_group;
            if (explicit_entry >= 0)
            {
                const BoundaryEntry& entry = setup.boundary[explicit_entry];
                throw ParseError(dict, entry.line,
                                 "boundary entry '" + entry.key + "': patch '" + patch.name +
                                     "' is of type " + patch.type +
                                     " and keeps OpenFOAM's meaning (" +
                                     (patch.type == "empty" ? "2D: no motion normal to the plane"
                                                            : "points slide within the plane") +
                                     "); remove the entry");
            }
            a.motion = patch.type == "empty" ? MotionType::free : MotionType::slip;
            a.matched_by = patch.type;
            result.push_back(a);
            continue;
        }
        if (by_name >= 0)
        {
            a.entry = by_name;
            a.matched_by = "name";
        }
        else if (by_group >= 0)
        {
            a.entry = by_group;
            a.matched_by = "group " + group_name;
        }
        else if (by_regex >= 0)
        {
            a.entry = by_regex;
            a.matched_by = "regex \"" + setup.boundary[by_regex].key + "\"";
        }
        else if (default_entry >= 0)
        {
            a.entry = default_entry;
            a.matched_by = "default";
            entry_used[default_entry] = 1;
        }
        else
        {
            a.matched_by = "default (fixed)";
        }
        a.motion = a.entry >= 0 ? setup.boundary[a.entry].motion.type : MotionType::fixed;
        result.push_back(a);
    }

    // Every literal key must name a patch or group; every regex must match a patch.
    for (std::size_t e = 0; e < setup.boundary.size(); ++e)
    {
        const BoundaryEntry& entry = setup.boundary[e];
        if (entry_used[e] || (!entry.is_regex && entry.key == "default"))
            continue;
        bool names_something = false;
        for (const Patch& patch : mesh.patches)
        {
            const std::vector<std::string> groups = patch_groups(patch);
            if (entry.is_regex ? std::regex_match(patch.name, *regexes[e])
                               : (patch.name == entry.key || std::find(groups.begin(), groups.end(),
                                                                       entry.key) != groups.end()))
                names_something = true; // e.g. a regex matching only empty patches
        }
        if (names_something)
            continue;
        std::string names;
        for (const Patch& patch : mesh.patches)
            names += (names.empty() ? "" : " ") + patch.name;
        throw ParseError(dict, entry.line,
                         "boundary entry " + entry_label(entry) +
                             (entry.is_regex ? ": regular expression matches no patch"
                                             : ": no patch or patch group of that name") +
                             " (patches: " + names + ")");
    }
    return result;
}

namespace
{

//! A dictionary that asks for motion (a non-zero prescription or handle) but resolves to
//! none (every moving point also held by a conflict rule, say) is an error: a quiet success
//! that writes unchanged points would mislead.
void require_some_motion(const std::vector<Claim>& claims, const MorphSetup& setup,
                         const std::vector<Vector3>& values, const Constraints& out,
                         double tolerance)
{
    const bool asked =
        std::any_of(claims.begin(), claims.end(),
                    [&](const Claim& c)
                    { return c.kind == Claim::Kind::value && c.value.norm() > tolerance; }) ||
        std::any_of(setup.handles.begin(), setup.handles.end(),
                    [&](const HandleEntry& h) { return h.displacement.norm() > tolerance; });
    const bool moves = std::any_of(values.begin(), values.end(),
                                   [&](const Vector3& v) { return v.norm() > tolerance; });
    if (!asked || moves)
        return;
    std::string list;
    for (const std::string& line : out.conflict_summary)
        list += "\n    " + line;
    throw InvalidInput(setup.dict_path +
                       ": the dictionary asks for motion but every prescribed displacement "
                       "resolves to zero, so nothing would move" +
                       (list.empty()
                            ? std::string(".")
                            : " (conflicts resolved by rule '" + to_string(setup.conflicts) +
                                  "':" + list + "\n  set 'conflicts' to first, last or average)"));
}

} // namespace

namespace
{

//! Per point, the length of its shortest edge on a boundary face (infinity off the
//! boundary).
std::vector<double> shortest_boundary_edges(const PolyMesh& mesh)
{
    std::vector<double> shortest(static_cast<std::size_t>(mesh.n_points()),
                                 std::numeric_limits<double>::infinity());
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
    {
        const std::span<const Index> face = mesh.faces[f];
        for (std::size_t i = 0; i < face.size(); ++i)
        {
            const Index a = face[i], b = face[(i + 1) % face.size()];
            const double l = (mesh.points.row(a) - mesh.points.row(b)).norm();
            shortest[static_cast<std::size_t>(a)] =
                std::min(shortest[static_cast<std::size_t>(a)], l);
            shortest[static_cast<std::size_t>(b)] =
                std::min(shortest[static_cast<std::size_t>(b)], l);
        }
    }
    return shortest;
}

//! The mesh point nearest to x; in a 2D case (empty_normal set) the nearest in the plane of
//! the case, on every empty plane (within `tolerance` of the nearest), so that a handle
//! moves both points of a pair, as the 2D motion needs.
std::vector<Index> nearest_points(const PolyMesh& mesh, const Vector3& x,
                                  const std::optional<Vector3>& empty_normal, double tolerance)
{
    Eigen::MatrixXd d = mesh.points.rowwise() - x.transpose();
    if (empty_normal)
        d -= (d * *empty_normal) * empty_normal->transpose();
    const Eigen::VectorXd dist = d.rowwise().norm();
    Eigen::Index nearest = 0;
    const double closest = dist.minCoeff(&nearest);
    if (!empty_normal)
        return {static_cast<Index>(nearest)};
    std::vector<Index> out;
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (dist[p] <= closest + tolerance)
            out.push_back(p);
    return out;
}

} // namespace

Constraints build_constraints(const PolyMesh& mesh, const MorphSetup& setup,
                              const ConstraintInputs& inputs)
{
    const std::string& dict = setup.dict_path;
    Constraints out;
    out.conflict_rule = setup.conflicts;
    out.patches = inputs.patches != nullptr ? *inputs.patches : assign_patches(mesh, setup);
    const double diag = mesh_diagonal(mesh);
    // Two prescriptions agree when they differ by less than this: far below any motion
    // meaningful for a mesh, far above round-off of the closed-form motions.
    const double agree_tol = 1e-12 * diag;
    const double in_plane_tol = 1e-5; // relative; 10x patch_plane's planarity tolerance
    // Prescriptions of a point that differ by at most this fraction of its shortest
    // boundary edge agree "to the mesh's resolution" (see the resolution loop).
    const double near_agreement = 0.1;
    const std::vector<double> edge_lengths = shortest_boundary_edges(mesh);

    // 2D cases: the empty planes must be parallel.
    for (std::size_t pi = 0; pi < mesh.patches.size(); ++pi)
    {
        const Patch& patch = mesh.patches[pi];
        if (patch.type != "empty")
            continue;
        for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
        {
            const Vector3 a = face_area_vector(mesh, mesh.faces[f]);
            if (a.norm() <= constants::vsmall)
                continue;
            const Vector3 n = a.normalized();
            if (!out.empty_normal)
            {
                out.empty_normal = n;
                out.empty_offset = n.dot(mesh.points.row(mesh.faces[f][0]).transpose());
            }
            else if (n.cross(*out.empty_normal).norm() > 1e-6)
                throw InvalidInput("empty patch '" + patch.name +
                                   "' is not parallel to the other empty planes: morphMesh "
                                   "keeps 2D cases 2D only when they are extruded along one "
                                   "direction");
        }
    }

    // Collect claims per point.
    std::vector<Claim> claims;
    std::map<std::string, std::vector<std::pair<Index, Index>>>
        surface_requests;                               // file -> (claim, point)
    std::map<std::string, std::string> surface_entries; // file -> "boundary entry ..." for messages
    std::map<std::string, std::size_t> surface_lines;
    for (std::size_t pi = 0; pi < mesh.patches.size(); ++pi)
    {
        const Patch& patch = mesh.patches[pi];
        const PatchAssignment& a = out.patches[pi];
        if (patch.type == "empty" || patch.n_faces == 0)
            continue;
        const std::vector<Index> pts = patch_points(mesh, patch);
        const Index order = a.entry;
        const Motion motion = a.entry >= 0 ? setup.boundary[a.entry].motion : Motion{};
        const std::size_t line = a.entry >= 0 ? setup.boundary[a.entry].line : 0;
        const std::string what =
            a.entry >= 0 ? "boundary entry " + entry_label(setup.boundary[a.entry]) : "";

        if (patch.type == "wedge" || motion.type == MotionType::slip)
        {
            const auto plane = patch_plane(mesh, patch);
            if (!plane)
            {
                if (patch.type == "wedge")
                    throw InvalidInput("wedge patch '" + patch.name + "' is not planar");
                throw ParseError(dict, line,
                                 what + ": patch '" + patch.name +
                                     "' is not planar, so type slip cannot keep its points on "
                                     "it (use type surface with the patch's geometry instead)");
            }
            for (Index p : pts)
                claims.push_back(
                    {p, static_cast<Index>(pi), order, Claim::Kind::slip, plane->first});
            continue;
        }
        switch (motion.type)
        {
        case MotionType::free:
            for (Index p : pts)
                claims.push_back(
                    {p, static_cast<Index>(pi), order, Claim::Kind::free, Vector3::Zero()});
            break;
        case MotionType::point_displacement:
            if (inputs.point_displacement == nullptr)
                throw ParseError(dict, line,
                                 what + ": type pointDisplacement needs a "
                                        "pointDisplacement field, none was read");
            if (inputs.point_displacement->rows() != mesh.n_points())
                throw InvalidInput(
                    "pointDisplacement has " + std::to_string(inputs.point_displacement->rows()) +
                    " values, the mesh has " + std::to_string(mesh.n_points()) + " points");
            if (inputs.patch_point_displacement != nullptr &&
                pi < inputs.patch_point_displacement->size() &&
                (*inputs.patch_point_displacement)[pi].has_value())
            {
                const Points& values = *(*inputs.patch_point_displacement)[pi];
                if (values.rows() != static_cast<Eigen::Index>(pts.size()))
                    throw InvalidInput("pointDisplacement values of patch '" + patch.name +
                                       "' do not match its number of points");
                for (std::size_t i = 0; i < pts.size(); ++i)
                    claims.push_back({pts[i], static_cast<Index>(pi), order, Claim::Kind::value,
                                      values.row(static_cast<Eigen::Index>(i)).transpose()});
                break;
            }
            for (Index p : pts)
                claims.push_back({p, static_cast<Index>(pi), order, Claim::Kind::value,
                                  inputs.point_displacement->row(p).transpose()});
            break;
        case MotionType::surface:
            if (!inputs.project_to_surface)
                throw ParseError(dict, line,
                                 what + ": type surface needs a target surface "
                                        "reader, none was given");
            surface_entries.try_emplace(motion.file, what);
            surface_lines.try_emplace(motion.file, line);
            for (Index p : pts)
            {
                surface_requests[motion.file].emplace_back(static_cast<Index>(claims.size()), p);
                claims.push_back(
                    {p, static_cast<Index>(pi), order, Claim::Kind::value, Vector3::Zero()});
            }
            break;
        default:
        {
            Index rotation = -1;
            if (motion.type == MotionType::rotate)
            {
                rotation = static_cast<Index>(out.rotations.size());
                out.rotations.push_back(motion);
            }
            for (Index p : pts)
            {
                // 2D: evaluate at the projection onto the reference empty plane, so both
                // planes get the same prescription (a rotation about a tilted axis would
                // otherwise differ between them).
                Vector3 x = mesh.points.row(p).transpose();
                if (out.empty_normal)
                    x -= (out.empty_normal->dot(x) - out.empty_offset) * *out.empty_normal;
                claims.push_back({p, static_cast<Index>(pi), order, Claim::Kind::value,
                                  motion.displacement(x), rotation});
            }
        }
        }
    }
    for (const auto& [file, requests] : surface_requests)
    {
        Points query(static_cast<Eigen::Index>(requests.size()), 3);
        for (std::size_t i = 0; i < requests.size(); ++i)
            query.row(static_cast<Eigen::Index>(i)) = mesh.points.row(requests[i].second);
        Points closest;
        try
        {
            closest = inputs.project_to_surface(file, query);
        }
        catch (const Error& e)
        {
            // Name the dictionary entry as well as the surface file.
            throw ParseError(dict, surface_lines[file],
                             surface_entries[file] + ": cannot use surface \"" + file +
                                 "\": " + e.what());
        }
        if (closest.rows() != query.rows())
            throw std::logic_error("project_to_surface returned a wrong number of points");
        for (std::size_t i = 0; i < requests.size(); ++i)
            claims[requests[i].first].value = (closest.row(static_cast<Eigen::Index>(i)) -
                                               query.row(static_cast<Eigen::Index>(i)))
                                                  .transpose();
    }
    std::stable_sort(claims.begin(), claims.end(),
                     [](const Claim& a, const Claim& b) { return a.point < b.point; });

    // Resolve per point. Final state: value (displacement), slip (projector) or none.
    struct Resolved
    {
        Index point;
        bool is_slip;
        Vector3 value;
        Eigen::Matrix3d projector;
        Index rotation = -1;
    };
    std::vector<Resolved> resolved;
    resolved.reserve(claims.size());
    std::map<std::string, Index> conflict_pairs;
    for (std::size_t begin = 0; begin < claims.size();)
    {
        std::size_t end = begin;
        while (end < claims.size() && claims[end].point == claims[begin].point)
            ++end;
        const Index point = claims[begin].point;
        std::vector<const Claim*> values;
        std::vector<const Claim*> slips;
        for (std::size_t i = begin; i < end; ++i)
        {
            if (claims[i].kind == Claim::Kind::value)
                values.push_back(&claims[i]);
            else if (claims[i].kind == Claim::Kind::slip)
                slips.push_back(&claims[i]);
        }
        begin = end;
        if (values.empty() && slips.empty())
        {
            ++out.n_free_points;
            continue;
        }
        bool conflict = false;
        double spread = 0.0; // how far apart the prescriptions are
        for (const Claim* c : values)
        {
            spread = std::max(spread, (c->value - values.front()->value).norm());
            if ((c->value - values.front()->value).norm() > agree_tol)
                conflict = true;
        }
        const bool values_agree = !conflict;
        // A motion leaves a slip (or wedge) plane when its normal component exceeds the
        // tolerance to which the patch was found planar (patch_plane: 1e-6 of its size),
        // relative to the motion: a translation along a wedge's axis, written to 6 digits,
        // stays in both wedge planes.
        if (!values.empty())
            for (const Claim* s : slips)
            {
                spread = std::max(spread, std::abs(values.front()->value.dot(s->value)));
                if (std::abs(values.front()->value.dot(s->value)) >
                    in_plane_tol * values.front()->value.norm() + agree_tol)
                    conflict = true;
            }

        const auto slip_result = [&](const std::vector<const Claim*>& planes)
        {
            std::vector<Vector3> normals;
            for (const Claim* s : planes)
                normals.push_back(s->value);
            int rank = 0;
            const Eigen::Matrix3d P = slip_projector(normals, rank);
            if (rank >= 3) // three independent planes: the point cannot move
                return Resolved{point, false, Vector3::Zero(), Eigen::Matrix3d::Identity()};
            return Resolved{point, true, Vector3::Zero(), P};
        };

        // snappyHexMesh leaves the points of patch edges micrometres off the surfaces, so a
        // projection moves them a little where a neighbouring patch holds or slides them:
        // a difference far below the cells' size is no conflict worth a warning. A value
        // that leaves a slip plane by that little is projected into it; values that differ
        // by that little are resolved by the rule (fixed, the default, holds the point).
        const bool near =
            conflict && spread <= near_agreement * edge_lengths[static_cast<std::size_t>(point)];
        if (near)
        {
            ++out.n_near_agreements;
            out.max_near_agreement = std::max(
                out.max_near_agreement, spread / edge_lengths[static_cast<std::size_t>(point)]);
            conflict = !values_agree;
        }
        if (!conflict)
        {
            if (values.empty())
                resolved.push_back(slip_result(slips));
            else if (slips.empty())
                resolved.push_back({point, false, values.front()->value,
                                    Eigen::Matrix3d::Identity(), values.front()->rotation});
            else // in the planes to round-off: exactly in them
                resolved.push_back({point, false,
                                    slip_result(slips).projector * values.front()->value,
                                    Eigen::Matrix3d::Identity(), values.front()->rotation});
            continue;
        }

        if (!near)
        {
            ++out.n_conflicts;
            std::set<std::string> names;
            for (const Claim* c : values)
                names.insert(mesh.patches[c->patch].name);
            for (const Claim* c : slips)
                names.insert(mesh.patches[c->patch].name);
            std::string key;
            for (const std::string& n : names)
                key += (key.empty() ? "" : "/") + n;
            ++conflict_pairs[key];
        }

        switch (setup.conflicts)
        {
        case ConflictRule::error:
        case ConflictRule::fixed:
            resolved.push_back({point, false, Vector3::Zero(), Eigen::Matrix3d::Identity()});
            break;
        case ConflictRule::average:
        {
            Vector3 mean = Vector3::Zero();
            for (const Claim* c : values)
                mean += c->value;
            mean /= static_cast<double>(values.size());
            resolved.push_back({point, false, mean, Eigen::Matrix3d::Identity()});
            break;
        }
        case ConflictRule::first:
        case ConflictRule::last:
        {
            const Claim* winner = nullptr;
            for (const Claim* c : values)
                if (winner == nullptr ||
                    (setup.conflicts == ConflictRule::first ? c->order < winner->order
                                                            : c->order > winner->order))
                    winner = c;
            for (const Claim* c : slips)
                if (setup.conflicts == ConflictRule::first ? c->order < winner->order
                                                           : c->order > winner->order)
                    winner = c;
            if (winner->kind == Claim::Kind::slip)
                resolved.push_back(slip_result(slips));
            else
                resolved.push_back(
                    {point, false, winner->value, Eigen::Matrix3d::Identity(), winner->rotation});
            break;
        }
        }
    }
    for (const auto& [names, count] : conflict_pairs)
        out.conflict_summary.push_back(names + ": " + std::to_string(count) + " points");
    if (out.n_conflicts > 0 && setup.conflicts == ConflictRule::error)
    {
        std::string list;
        for (const std::string& s : out.conflict_summary)
            list += "\n    " + s;
        throw InvalidInput(dict + ": " + std::to_string(out.n_conflicts) +
                           " points lie on patches with different prescriptions (conflicts "
                           "error):" +
                           list +
                           "\n  set 'conflicts' to fixed, first, last or average to resolve them");
    }

    // Handles: selected points, later handles checked against earlier ones.
    std::map<Index, std::pair<Vector3, std::vector<Index>>>
        handle_values; // point -> (value, handles)
    for (std::size_t h = 0; h < setup.handles.size(); ++h)
    {
        const HandleEntry& handle = setup.handles[h];
        std::vector<Index> selected;
        switch (handle.selection)
        {
        case HandleEntry::Selection::point_zone:
        {
            auto it = std::find_if(mesh.point_zones.begin(), mesh.point_zones.end(),
                                   [&](const Zone& z) { return z.name == handle.zone; });
            if (it == mesh.point_zones.end())
            {
                std::string zones;
                for (const Zone& z : mesh.point_zones)
                    zones += (zones.empty() ? "" : " ") + z.name;
                throw ParseError(
                    dict, handle.line,
                    "handles entry '" + handle.name + "': no pointZone '" + handle.zone +
                        "' in the mesh (pointZones: " + (zones.empty() ? "none" : zones) + ")");
            }
            selected = it->labels;
            break;
        }
        case HandleEntry::Selection::box:
            for (Index p = 0; p < mesh.n_points(); ++p)
            {
                const Vector3 x = mesh.points.row(p).transpose();
                if ((x.array() >= handle.box_min.array()).all() &&
                    (x.array() <= handle.box_max.array()).all())
                    selected.push_back(p);
            }
            break;
        case HandleEntry::Selection::points:
            for (Eigen::Index k = 0; k < handle.points.rows(); ++k)
                for (Index p : nearest_points(mesh, handle.points.row(k).transpose(),
                                              out.empty_normal, agree_tol))
                    selected.push_back(p);
            break;
        }
        if (selected.empty())
            throw ParseError(dict, handle.line,
                             "handles entry '" + handle.name + "' selects no mesh point");
        for (Index p : selected)
        {
            if (p < 0 || p >= mesh.n_points())
                throw InvalidInput("pointZone '" + handle.zone + "' has point label " +
                                   std::to_string(p) + " out of range");
            auto [it, inserted] = handle_values.try_emplace(
                p, handle.displacement, std::vector<Index>{static_cast<Index>(h)});
            if (inserted)
                continue;
            if (std::find(it->second.second.begin(), it->second.second.end(),
                          static_cast<Index>(h)) != it->second.second.end())
                continue; // the same handle listing a point twice
            it->second.second.push_back(static_cast<Index>(h));
        }
    }
    // Handle conflicts (overlapping handles that disagree).
    std::map<std::string, Index> handle_conflicts;
    for (auto& [p, entry] : handle_values)
    {
        std::vector<Index>& hs = entry.second;
        if (hs.size() < 2)
            continue;
        bool agree = true;
        for (Index h : hs)
            if ((setup.handles[h].displacement - setup.handles[hs.front()].displacement).norm() >
                agree_tol)
                agree = false;
        if (agree)
            continue;
        ++out.n_conflicts;
        std::string key = "handles";
        for (Index h : hs)
            key += " " + setup.handles[h].name;
        ++handle_conflicts[key];
        switch (setup.conflicts)
        {
        case ConflictRule::error:
        case ConflictRule::fixed:
            entry.first = Vector3::Zero();
            break;
        case ConflictRule::first:
            entry.first = setup.handles[hs.front()].displacement;
            break;
        case ConflictRule::last:
            entry.first = setup.handles[hs.back()].displacement;
            break;
        case ConflictRule::average:
        {
            Vector3 mean = Vector3::Zero();
            for (Index h : hs)
                mean += setup.handles[h].displacement;
            entry.first = mean / static_cast<double>(hs.size());
            break;
        }
        }
    }
    for (const auto& [names, count] : handle_conflicts)
        out.conflict_summary.push_back(names + ": " + std::to_string(count) + " points");
    if (!handle_conflicts.empty() && setup.conflicts == ConflictRule::error)
        throw InvalidInput(dict + ": overlapping handles prescribe different displacements (" +
                           handle_conflicts.begin()->first +
                           "); set 'conflicts' to fixed, first, last or average");
    out.n_handle_points = static_cast<Index>(handle_values.size());

    // Merge: handles override boundary prescriptions.
    std::vector<Index> points;
    std::vector<Vector3> values;
    auto hv = handle_values.begin();
    const auto take_handles_below = [&](Index limit)
    {
        while (hv != handle_values.end() && hv->first < limit)
        {
            points.push_back(hv->first);
            values.push_back(hv->second.first);
            out.rotation_of.push_back(-1);
            ++hv;
        }
    };
    for (const Resolved& r : resolved)
    {
        take_handles_below(r.point);
        if (hv != handle_values.end() && hv->first == r.point)
        {
            ++out.n_handle_overrides;
            take_handles_below(r.point + 1);
            continue;
        }
        if (r.is_slip)
        {
            out.slip_points.push_back(r.point);
            out.slip_projectors.push_back(r.projector);
        }
        else
        {
            points.push_back(r.point);
            values.push_back(r.value);
            out.rotation_of.push_back(r.rotation);
        }
    }
    take_handles_below(std::numeric_limits<Index>::max());

    require_some_motion(claims, setup, values, out, agree_tol);
    out.points = std::move(points);
    out.displacements.resize(static_cast<Eigen::Index>(values.size()), 3);
    for (std::size_t i = 0; i < values.size(); ++i)
    {
        Vector3 v = values[i];
        if (out.empty_normal)
            v -= v.dot(*out.empty_normal) * *out.empty_normal;
        out.displacements.row(static_cast<Eigen::Index>(i)) = v.transpose();
    }
    return out;
}

} // namespace meshmorph::app
