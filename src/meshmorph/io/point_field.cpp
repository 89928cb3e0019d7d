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

} // namespace

PointVectorField read_point_vector_field(const fs::path& path, const PolyMesh& mesh)
{
    const FoamDictionary dict = read_dictionary(path);
    PointVectorField field;
    field.path = path;
    if (!dict.header())
        throw ParseError(path.string(), 1, "missing FoamFile header");
    field.header = *dict.header();
    if (field.header.class_name != "pointVectorField")
        throw ParseError(path.string(), field.header.line,
                         "wrong class '" + field.header.class_name +
                             "' in FoamFile header, expected pointVectorField");

    const std::size_t n_points = static_cast<std::size_t>(mesh.n_points());
    field.internal = read_vector_value(dict.entry("internalField"), n_points, "the mesh",
                                       field.internal_is_uniform);

    const FoamDictionary& boundary = dict.sub_dict("boundaryField");
    const std::vector<FoamEntry>& entries = boundary.entries();
    field.patches.resize(mesh.patches.size());
    std::vector<const FoamEntry*> chosen(mesh.patches.size(), nullptr);

    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
    {
        const Patch& patch = mesh.patches[p];
        PointPatchField& pf = field.patches[p];
        pf.patch = patch.name;
        // 1. exact name.
        for (auto it = entries.rbegin(); it != entries.rend() && !chosen[p]; ++it)
            if (!it->is_regex() && it->keyword() == patch.name)
            {
                chosen[p] = &*it;
                pf.matched_by = PointPatchField::Match::name;
            }
        // 2. patch group (the entry written last wins).
        if (!chosen[p])
        {
            const std::vector<std::string> groups = patch_groups(patch);
            for (auto it = entries.rbegin(); it != entries.rend() && !chosen[p]; ++it)
                if (!it->is_regex() &&
                    std::find(groups.begin(), groups.end(), it->keyword()) != groups.end())
                {
                    chosen[p] = &*it;
                    pf.matched_by = PointPatchField::Match::group;
                }
        }
        // 3. an empty patch without entry is `empty` (before regex keys, as OpenFOAM).
        if (!chosen[p] && patch.type == "empty")
        {
            pf.type = "empty";
            pf.matched_by = PointPatchField::Match::empty_default;
            continue;
        }
        // 4. regex keys, the one written last first.
        if (!chosen[p])
        {
            const FoamEntry* e = boundary.find(patch.name);
            if (e && e->is_regex())
            {
                chosen[p] = e;
                pf.matched_by = PointPatchField::Match::regex;
            }
        }
        if (!chosen[p])
            throw boundary.error("Cannot find patchField entry for " + patch.name);

        const FoamEntry& entry = *chosen[p];
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
            continue;
        }
        if (pf.type != "fixedValue" && pf.type != "calculated")
            throw bc.entry("type").error(where + ": unsupported patchField type '" + pf.type +
                                         "' (meshmorph supports fixedValue, calculated with a "
                                         "value, and the constraint types)");
        if (!bc.found("value"))
            throw bc.error(where + ": type " + pf.type + " needs a 'value' entry");
        const std::size_t n_patch_points = patch_points(mesh, patch).size();
        pf.value = read_vector_value(bc.entry("value"), n_patch_points, "patch " + patch.name,
                                     pf.is_uniform);
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
