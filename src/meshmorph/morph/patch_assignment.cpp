// SPDX-License-Identifier: GPL-3.0-or-later
// Matching morphDict boundary entries to patches: name, group, regex, default.
#include "meshmorph/morph/patch_assignment.h"

#include <algorithm>
#include <optional>
#include <regex>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/mesh/patch_kinds.h"

namespace meshmorph::morph
{

namespace
{

bool is_constraint_type(const std::string& type)
{
    return type == "empty" || type == "wedge";
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

using Regexes = std::vector<std::optional<std::regex>>;

//! The compiled regex of every quoted key (nullopt for literal keys); a bad regex is a
//! dictionary error.
Regexes compile_regexes(const MorphSetup& setup)
{
    Regexes regexes(setup.boundary.size());
    for (std::size_t e = 0; e < setup.boundary.size(); ++e)
    {
        const BoundaryEntry& entry = setup.boundary[e];
        if (!entry.is_regex)
            continue;
        try
        {
            regexes[e].emplace(entry.key, io::keyword_regex_flags);
        }
        catch (const std::regex_error& err)
        {
            throw ParseError(setup.dict_path, entry.line,
                             "boundary entry \"" + entry.key + "\": invalid regular expression (" +
                                 err.what() + ")");
        }
    }
    return regexes;
}

//! The entries that match one patch, by kind (-1: none).
struct Matches
{
    Index by_name = -1;
    Index by_group = -1;
    Index by_regex = -1; //!< the last matching regex written
    std::string group;   //!< the group by_group names
};

Matches match_entries(const Patch& patch, const MorphSetup& setup, const Regexes& regexes,
                      std::vector<char>& entry_used)
{
    const std::vector<std::string> groups = patch_groups(patch);
    Matches m;
    for (std::size_t e = 0; e < setup.boundary.size(); ++e)
    {
        const BoundaryEntry& entry = setup.boundary[e];
        if (entry.is_regex)
        {
            if (!std::regex_match(patch.name, *regexes[e]))
                continue;
            m.by_regex = static_cast<Index>(e);
        }
        else if (entry.key == patch.name)
            m.by_name = static_cast<Index>(e);
        else if (std::find(groups.begin(), groups.end(), entry.key) != groups.end())
        {
            m.by_group = static_cast<Index>(e); // entries later in the file win
            m.group = entry.key;
        }
        else
            continue;
        entry_used[e] = 1;
    }
    return m;
}

//! empty and wedge patches: their own motion. Naming one explicitly (by name or group) with
//! a motion would change its OpenFOAM meaning; regex and default entries simply skip it.
void assign_constraint_patch(const Patch& patch, const Matches& m, const MorphSetup& setup,
                             PatchAssignment& a)
{
    const Index explicit_entry = m.by_name >= 0 ? m.by_name : m.by_group;
    if (explicit_entry >= 0)
    {
        const BoundaryEntry& entry = setup.boundary[explicit_entry];
        throw ParseError(setup.dict_path, entry.line,
                         "boundary entry '" + entry.key + "': patch '" + patch.name +
                             "' is of type " + patch.type + " and keeps OpenFOAM's meaning (" +
                             (patch.type == "empty" ? "2D: no motion normal to the plane"
                                                    : "points slide within the plane") +
                             "); remove the entry");
    }
    a.motion = patch.type == "empty" ? MotionType::free : MotionType::slip;
    a.matched_by = patch.type;
}

//! Name, then group, then regex, then default.
void assign_by_precedence(const Matches& m, Index default_entry, const MorphSetup& setup,
                          PatchAssignment& a)
{
    if (m.by_name >= 0)
    {
        a.entry = m.by_name;
        a.matched_by = "name";
    }
    else if (m.by_group >= 0)
    {
        a.entry = m.by_group;
        a.matched_by = "group " + m.group;
    }
    else if (m.by_regex >= 0)
    {
        a.entry = m.by_regex;
        a.matched_by = "regex \"" + setup.boundary[m.by_regex].key + "\"";
    }
    else if (default_entry >= 0)
    {
        a.entry = default_entry;
        a.matched_by = "default";
    }
    else
        a.matched_by = "default (fixed)";
    a.motion = a.entry >= 0 ? setup.boundary[a.entry].motion.type : MotionType::fixed;
}

//! The literal `default` entry (the last one written), -1 if none.
Index find_default_entry(const MorphSetup& setup)
{
    Index found = -1;
    for (std::size_t e = 0; e < setup.boundary.size(); ++e)
        if (!setup.boundary[e].is_regex && setup.boundary[e].key == "default")
            found = static_cast<Index>(e);
    return found;
}

bool names_some_patch(const PolyMesh& mesh, const BoundaryEntry& entry,
                      const std::optional<std::regex>& regex)
{
    for (const Patch& patch : mesh.patches)
    {
        const std::vector<std::string> groups = patch_groups(patch);
        if (entry.is_regex ? std::regex_match(patch.name, *regex)
                           : (patch.name == entry.key ||
                              std::find(groups.begin(), groups.end(), entry.key) != groups.end()))
            return true; // e.g. a regex matching only empty patches
    }
    return false;
}

//! Every literal key must name a patch or group; every regex must match a patch.
void require_every_entry_used(const PolyMesh& mesh, const MorphSetup& setup, const Regexes& regexes,
                              const std::vector<char>& entry_used)
{
    for (std::size_t e = 0; e < setup.boundary.size(); ++e)
    {
        const BoundaryEntry& entry = setup.boundary[e];
        if (entry_used[e] || (!entry.is_regex && entry.key == "default") ||
            names_some_patch(mesh, entry, regexes[e]))
            continue;
        std::string names;
        for (const Patch& patch : mesh.patches)
            names += (names.empty() ? "" : " ") + patch.name;
        throw ParseError(setup.dict_path, entry.line,
                         "boundary entry " + entry_label(entry) +
                             (entry.is_regex ? ": regular expression matches no patch"
                                             : ": no patch or patch group of that name") +
                             " (patches: " + names + ")");
    }
}

} // namespace

std::vector<PatchAssignment> assign_patches(const PolyMesh& mesh, const MorphSetup& setup,
                                            bool decomposed)
{
    const Regexes regexes = compile_regexes(setup);
    const Index default_entry = find_default_entry(setup);
    std::vector<char> entry_used(setup.boundary.size(), 0);
    std::vector<PatchAssignment> result;
    result.reserve(mesh.patches.size());
    for (const Patch& patch : mesh.patches)
    {
        if (is_processor_patch(patch) && !decomposed)
            throw InvalidInput("patch '" + patch.name + "' is of type " + patch.type +
                               ": a processor directory is part of a decomposed case (run "
                               "morphMesh -parallel on the case, or on the reconstructed case)");
        if (is_processor_patch(patch))
        {
            result.push_back({patch.name, patch.type, MotionType::free, "processor", -1, 0});
            continue;
        }
        const Matches m = match_entries(patch, setup, regexes, entry_used);
        PatchAssignment a;
        a.patch = patch.name;
        a.patch_type = patch.type;
        a.n_points = static_cast<Index>(patch_points(mesh, patch).size());
        if (is_constraint_type(patch.type))
            assign_constraint_patch(patch, m, setup, a);
        else
            assign_by_precedence(m, default_entry, setup, a);
        result.push_back(a);
    }
    require_every_entry_used(mesh, setup, regexes, entry_used);
    return result;
}

} // namespace meshmorph::morph
