// SPDX-License-Identifier: GPL-3.0-or-later
// pointVectorField reader: dictionary parsing (foam_dictionary), OpenFOAM's patch matching.
#include "meshmorph/io/point_field.h"

#include <algorithm>
#include <array>
#include <cstring>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_dictionary.h"

namespace meshmorph::io
{
namespace fs = std::filesystem;

namespace
{

constexpr std::array<const char*, 7> constraint_types{
    "empty", "wedge", "symmetryPlane", "symmetry", "cyclic", "cyclicAMI", "processor"};

bool is_constraint_type(const std::string& type)
{
    return std::find(constraint_types.begin(), constraint_types.end(), type) !=
           constraint_types.end();
}

// Patch groups of a patch: inGroups, plus the group OpenFOAM adds for wall and constraint
// patch types.
std::vector<std::string> patch_groups(const Patch& patch)
{
    std::vector<std::string> groups = patch.in_groups;
    if ((patch.type == "wall" || is_constraint_type(patch.type)) &&
        std::find(groups.begin(), groups.end(), patch.type) == groups.end())
        groups.push_back(patch.type);
    return groups;
}

// `uniform (x y z)` or `nonuniform List<vector> N(...)` with N == expected rows.
Points read_vector_value(const FoamEntry& entry, std::size_t expected, const std::string& what,
                         bool& is_uniform)
{
    const std::vector<FoamValueToken>& t = entry.tokens();
    if (t.empty() || !t[0].is_word())
        throw entry.error("expected 'uniform (x y z)' or 'nonuniform List<vector> N(...)'");
    Points values;
    if (t[0].text == "uniform")
    {
        const Vector3 v = entry.get<Vector3>(1);
        values.resize(static_cast<Eigen::Index>(expected), 3);
        values.rowwise() = v.transpose();
        is_uniform = true;
        return values;
    }
    if (t[0].text != "nonuniform")
        throw entry.error("expected 'uniform' or 'nonuniform' but found " + t[0].describe());
    is_uniform = false;
    if (t.size() >= 2 && t[1].is_compound())
    {
        if (t.size() > 2)
            throw entry.error("unexpected " + t[2].describe() + " after the value list");
        const FoamCompound& c = *t[1].compound;
        if (c.kind != FoamCompound::Kind::vector)
            throw entry.error("expected a List<vector> but found " + c.type_word);
        const std::size_t n = c.size();
        if (n != expected)
            throw entry.error("has " + std::to_string(n) + " values but " + what + " has " +
                              std::to_string(expected) + " points");
        values.resize(static_cast<Eigen::Index>(n), 3);
        if (n > 0)
            std::memcpy(values.data(), c.scalars.data(), sizeof(double) * 3 * n);
        return values;
    }
    const std::vector<Vector3> list = entry.get<std::vector<Vector3>>(1);
    if (list.size() != expected)
        throw entry.error("has " + std::to_string(list.size()) + " values but " + what + " has " +
                          std::to_string(expected) + " points");
    values.resize(static_cast<Eigen::Index>(list.size()), 3);
    for (std::size_t i = 0; i < list.size(); ++i)
        values.row(static_cast<Eigen::Index>(i)) = list[i].transpose();
    return values;
}

// The dictionary's FoamFile header, which must say pointVectorField.
FoamHeader field_header(const FoamDictionary& dict, const fs::path& path)
{
    if (!dict.header())
        throw ParseError(path.string(), 1, "missing FoamFile header");
    const FoamHeader& header = *dict.header();
    if (header.class_name != "pointVectorField")
        throw ParseError(path.string(), header.line,
                         "wrong class '" + header.class_name +
                             "' in FoamFile header, expected pointVectorField");
    return header;
}

// The plain (not regex) entry named `patch`, the entry written last winning.
const FoamEntry* find_by_name(const std::vector<FoamEntry>& entries, const Patch& patch)
{
    for (auto it = entries.rbegin(); it != entries.rend(); ++it)
        if (!it->is_regex() && it->keyword() == patch.name)
            return &*it;
    return nullptr;
}

// The plain entry named after one of the patch's groups, the entry written last winning.
const FoamEntry* find_by_group(const std::vector<FoamEntry>& entries, const Patch& patch)
{
    const std::vector<std::string> groups = patch_groups(patch);
    for (auto it = entries.rbegin(); it != entries.rend(); ++it)
        if (!it->is_regex() &&
            std::find(groups.begin(), groups.end(), it->keyword()) != groups.end())
            return &*it;
    return nullptr;
}

// The regex entry matching the patch name, the one written last first.
const FoamEntry* find_by_regex(const FoamDictionary& boundary, const Patch& patch)
{
    const FoamEntry* e = boundary.find(patch.name);
    return e && e->is_regex() ? e : nullptr;
}

// The boundaryField entry of `patch`, in OpenFOAM's order of matching (recorded in
// pf.matched_by); nullptr for an empty patch without entry (then pf.type is `empty`).
// \throw the boundary's error when no entry matches.
const FoamEntry* match_patch_entry(const FoamDictionary& boundary, const Patch& patch,
                                   PointPatchField& pf)
{
    // 1. exact name.
    if (const FoamEntry* e = find_by_name(boundary.entries(), patch))
    {
        pf.matched_by = PointPatchField::Match::name;
        return e;
    }
    // 2. patch group (the entry written last wins).
    if (const FoamEntry* e = find_by_group(boundary.entries(), patch))
    {
        pf.matched_by = PointPatchField::Match::group;
        return e;
    }
    // 3. an empty patch without entry is `empty` (before regex keys, as OpenFOAM).
    if (patch.type == "empty")
    {
        pf.type = "empty";
        pf.matched_by = PointPatchField::Match::empty_default;
        return nullptr;
    }
    // 4. regex keys, the one written last first.
    if (const FoamEntry* e = find_by_regex(boundary, patch))
    {
        pf.matched_by = PointPatchField::Match::regex;
        return e;
    }
    throw boundary.error("Cannot find patchField entry for " + patch.name);
}

// The patchField `entry` of `patch`: a constraint type (which must be the patch's), or
// fixedValue / calculated with a value per patch point.
void read_patch_field(const FoamEntry& entry, const PolyMesh& mesh, const Patch& patch,
                      PointPatchField& pf, bool calculated_without_value)
{
    pf.key = entry.keyword();
    if (!entry.is_dict())
        throw entry.error("expected a dictionary { type ...; } for patch " + patch.name);
    const FoamDictionary& bc = entry.dict();
    pf.type = bc.get<std::string>("type");
    const std::string where = "patch '" + patch.name + "' (entry '" + entry.keyword() + "')";
    if (is_constraint_type(patch.type) || is_constraint_type(pf.type))
    {
        if (pf.type != patch.type)
            throw bc.entry("type").error(
                where + ": a patch of type " + patch.type + " needs the patchField type " +
                (is_constraint_type(patch.type) ? patch.type : "of its patch") + ", not " +
                pf.type);
        return;
    }
    if (pf.type != "fixedValue" && pf.type != "calculated")
        throw bc.entry("type").error(where + ": unsupported patchField type '" + pf.type +
                                     "' (meshmorph supports fixedValue, calculated with a "
                                     "value, and the constraint types)");
    if (!bc.found("value"))
    {
        if (calculated_without_value && pf.type == "calculated")
            return; // OpenFOAM writes a calculated pointPatchField without values
        throw bc.error(where + ": type " + pf.type + " needs a 'value' entry");
    }
    const std::size_t n_patch_points = patch_points(mesh, patch).size();
    pf.value =
        read_vector_value(bc.entry("value"), n_patch_points, "patch " + patch.name, pf.is_uniform);
}

} // namespace

PointVectorField read_point_vector_field(const fs::path& path, const PolyMesh& mesh,
                                         bool calculated_without_value)
{
    const FoamDictionary dict = read_dictionary(path);
    PointVectorField field;
    field.path = path;
    field.header = field_header(dict, path);

    const std::size_t n_points = static_cast<std::size_t>(mesh.n_points());
    field.internal = read_vector_value(dict.entry("internalField"), n_points, "the mesh",
                                       field.internal_is_uniform);

    const FoamDictionary& boundary = dict.sub_dict("boundaryField");
    field.patches.resize(mesh.patches.size());
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
    {
        const Patch& patch = mesh.patches[p];
        PointPatchField& pf = field.patches[p];
        pf.patch = patch.name;
        if (const FoamEntry* entry = match_patch_entry(boundary, patch, pf))
            read_patch_field(*entry, mesh, patch, pf, calculated_without_value);
    }
    return field;
}

PointVectorField read_point_vector_field(const fs::path& case_dir, const std::string& time,
                                         const std::string& name, const PolyMesh& mesh)
{
    return read_point_vector_field(case_dir / time / name, mesh);
}

Points apply_patch_values(const PointVectorField& field, const PolyMesh& mesh)
{
    Points values = field.internal;
    std::vector<Index> owner_patch(static_cast<std::size_t>(mesh.n_points()), -1);
    for (std::size_t p = 0; p < field.patches.size() && p < mesh.patches.size(); ++p)
    {
        const PointPatchField& pf = field.patches[p];
        if (!pf.value)
            continue;
        const std::vector<Index> points = patch_points(mesh, mesh.patches[p]);
        for (std::size_t i = 0; i < points.size(); ++i)
        {
            const Index pt = points[i];
            const Eigen::RowVector3d v = pf.value->row(static_cast<Eigen::Index>(i));
            const Index other = owner_patch[static_cast<std::size_t>(pt)];
            if (other >= 0 && values.row(pt) != v)
            {
                const Eigen::RowVector3d w = values.row(pt);
                throw InvalidInput(field.path.string() + ": point " + std::to_string(pt) +
                                   " is on patches '" +
                                   mesh.patches[static_cast<std::size_t>(other)].name + "' and '" +
                                   pf.patch + "' with different prescribed values (" +
                                   std::to_string(w.x()) + " " + std::to_string(w.y()) + " " +
                                   std::to_string(w.z()) + ") and (" + std::to_string(v.x()) + " " +
                                   std::to_string(v.y()) + " " + std::to_string(v.z()) +
                                   "); OpenFOAM's result would depend on the patch "
                                   "evaluation order");
            }
            values.row(pt) = v;
            owner_patch[static_cast<std::size_t>(pt)] = static_cast<Index>(p);
        }
    }
    return values;
}

} // namespace meshmorph::io
