// SPDX-License-Identifier: GPL-3.0-or-later
// The designVariables sub-dictionary, read and checked; lattices expanded into one variable
// per active control point and direction.
#include "meshmorph/design/design_variables.h"

#include <algorithm>
#include <set>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/morph/deformation_dict.h"
#include "meshmorph/morph/morph_setup.h"

namespace meshmorph::design
{

namespace
{

using morph::MotionType;

//! `patches (name "regex" ...);` or `patches name;`: the keys and whether each was quoted.
void read_patch_keys(const io::FoamEntry& e, std::vector<std::string>& keys,
                     std::vector<bool>& is_regex)
{
    const std::vector<io::FoamValueToken>& t = e.tokens();
    const bool list = !t.empty() && t.front().is_punct('(');
    const std::size_t first = list ? 1 : 0, last = list ? t.size() - 1 : t.size();
    if (list && !t.back().is_punct(')'))
        throw e.error("expected a list of patch names (name \"regex\" ...)");
    for (std::size_t i = first; i < last; ++i)
    {
        if (!t[i].is_word() && !t[i].is_string())
            throw e.error("expected a patch name, group or quoted regex, found " + t[i].describe());
        keys.push_back(t[i].text);
        is_regex.push_back(t[i].is_string());
    }
    if (keys.empty())
        throw e.error("expected at least one patch name");
}

//! `bounds (lower upper);` of a variable.
std::optional<std::pair<double, double>> read_amplitude_bounds(const io::FoamDictionary& d)
{
    const io::FoamEntry* e = d.find("bounds");
    if (e == nullptr)
        return std::nullopt;
    const std::vector<double> b = e->get<std::vector<double>>();
    if (b.size() != 2 || !(b[0] < b[1]))
        throw e->error("expected (lower upper) with lower < upper");
    return std::make_pair(b[0], b[1]);
}

//! A variable that moves patches: `patches (...); type <translate|rotate|scale|
//! pointDisplacement>; <parameters>; [bounds (lo hi);]`.
DesignVariable read_patch_variable(const io::FoamEntry& e)
{
    const io::FoamDictionary& d = e.dict();
    DesignVariable v;
    v.motion = morph::read_motion(e, {"patches", "bounds"});
    switch (v.motion.type)
    {
    case MotionType::translate:
    case MotionType::rotate:
    case MotionType::scale:
    case MotionType::point_displacement:
        break;
    case MotionType::surface:
        throw d.entry("type").error(
            "type surface is not a design variable: the nearest point on a surface is not "
            "linear in an amplitude (use translate, rotate, scale, pointDisplacement or a "
            "handle, or morph to the surface with a boundary entry)");
    default:
        throw d.entry("type").error("type " + morph::to_string(v.motion.type) +
                                    " does not move anything; a design variable is one of "
                                    "translate, rotate, scale, pointDisplacement or ffd");
    }
    read_patch_keys(d.entry("patches"), v.patch_keys, v.key_is_regex);
    v.bounds = read_amplitude_bounds(d);
    return v;
}

//! A variable that moves one handle's points: `handle <name>; vector (dx dy dz);` (a
//! translation), or `handle <name>; type translate|rotate|scale; <parameters>;`.
DesignVariable read_handle_variable(const io::FoamEntry& e)
{
    const io::FoamDictionary& d = e.dict();
    DesignVariable v;
    v.kind = DesignVariable::Kind::handle;
    if (d.found("type"))
    {
        v.motion = morph::read_motion(e, {"handle", "bounds"});
        if (v.motion.type != MotionType::translate && v.motion.type != MotionType::rotate &&
            v.motion.type != MotionType::scale)
            throw d.entry("type").error("a handle variable translates, rotates or scales its "
                                        "points, not type " +
                                        morph::to_string(v.motion.type));
    }
    else
    {
        d.check_keywords({"handle", "vector", "bounds"}, "a handle design variable");
        v.motion.type = MotionType::translate;
        v.motion.vector = d.get<Vector3>("vector");
        if (!v.motion.vector.allFinite())
            throw d.entry("vector").error("non-finite value");
    }
    v.handle = d.get<std::string>("handle");
    v.bounds = read_amplitude_bounds(d);
    return v;
}

//! `directions (x z);` of a lattice: the axes its control points move along.
std::vector<int> read_directions(const io::FoamDictionary& d)
{
    const io::FoamEntry* e = d.find("directions");
    if (e == nullptr)
        return {0, 1, 2};
    std::vector<int> axes;
    for (const std::string& w : e->get<std::vector<std::string>>())
    {
        if (w != "x" && w != "y" && w != "z")
            throw e->error("expected directions among x, y and z, found '" + w + "'");
        const int a = w[0] - 'x';
        if (std::find(axes.begin(), axes.end(), a) != axes.end())
            throw e->error("direction " + w + " given twice");
        axes.push_back(a);
    }
    if (axes.empty())
        throw e->error("expected at least one direction");
    return axes;
}

//! `confine (cx cy cz);`: outer layers of control points per axis that stay fixed. Three
//! make the lattice's motion fade to zero at its box (lattice_box_cut.h says why).
std::array<int, 3> read_confine(const io::FoamDictionary& d, const std::array<int, 3>& counts)
{
    const io::FoamEntry* e = d.find("confine");
    if (e == nullptr)
        return {0, 0, 0};
    const std::vector<std::int32_t> c = e->get<std::vector<std::int32_t>>();
    if (c.size() != 3)
        throw e->error("expected three layer counts (cx cy cz)");
    for (int a = 0; a < 3; ++a)
        if (c[std::size_t(a)] < 0 || 2 * c[std::size_t(a)] >= counts[std::size_t(a)])
            throw e->error("confine must leave at least one control point free per axis");
    return {c[0], c[1], c[2]};
}

//! `lattice (nx ny nz);`: each 1 (constant along that axis) or at least 4 (cubic).
std::array<int, 3> read_counts(const io::FoamEntry& e)
{
    const std::vector<std::int32_t> n = e.get<std::vector<std::int32_t>>();
    if (n.size() != 3)
        throw e.error("expected three control-point counts (nx ny nz)");
    for (std::int32_t v : n)
        if (v != 1 && (v < 4 || v > 1000))
            throw e.error("a cubic B-spline lattice needs 4 to 1000 control points per axis (or "
                          "1: constant along it, for 2D cases), got " +
                          std::to_string(v));
    // Each control point may be up to 3 variables, each a field over every point.
    if (double(n[0]) * n[1] * n[2] > 10000.0)
        throw e.error("more than 10000 control points: every one is a design variable with a "
                      "field over the whole mesh (use fewer, or a coarser lattice)");
    return {n[0], n[1], n[2]};
}

std::string axis_name(int a)
{
    return std::string(1, char('x' + a));
}

//! `type ffd; patches (...); lattice (nx ny nz); box ((..) (..)); [directions (..);]
//! [confine (..);] [bounds (lo hi);]`: one variable per free control point and direction.
void read_lattice_variables(const io::FoamEntry& e, DesignVariables& out)
{
    const io::FoamDictionary& d = e.dict();
    d.check_keywords({"type", "patches", "lattice", "box", "directions", "confine", "bounds"},
                     "type ffd");
    const std::optional<FfdBox> box = morph::read_bounds(d, "box");
    if (!box)
        throw e.error("type ffd needs box ((x0 y0 z0) (x1 y1 z1)) around the patches it moves");
    const std::array<int, 3> n = read_counts(d.entry("lattice"));
    std::array<int, 3> cubic = n;
    for (int& c : cubic)
        c = std::max(c, 4);
    DesignLattice lattice{e.keyword(), FfdLattice(*box, cubic), n, read_confine(d, n), {}, {},
                          e.line()};
    read_patch_keys(d.entry("patches"), lattice.patch_keys, lattice.key_is_regex);
    const std::array<int, 3> confine = lattice.confine;
    const std::vector<int> directions = read_directions(d);
    const auto bounds = read_amplitude_bounds(d);
    const std::size_t index = out.lattices.size();
    for (int k = confine[2]; k < n[2] - confine[2]; ++k)
        for (int j = confine[1]; j < n[1] - confine[1]; ++j)
            for (int i = confine[0]; i < n[0] - confine[0]; ++i)
                for (int a : directions)
                {
                    DesignVariable v;
                    v.name = e.keyword() + "." + std::to_string(i) + "." + std::to_string(j) + "." +
                             std::to_string(k) + "." + axis_name(a);
                    v.kind = DesignVariable::Kind::lattice_point;
                    v.lattice = index;
                    v.control_point = {i, j, k};
                    v.direction = a;
                    v.bounds = bounds;
                    v.line = e.line();
                    out.variables.push_back(std::move(v));
                }
    out.lattices.push_back(std::move(lattice));
}

void read_variable(const io::FoamEntry& e, DesignVariables& out)
{
    if (!e.is_dict())
        throw e.error("expected a sub-dictionary { patches (...); type translate; vector "
                      "(dx dy dz); } (or handle <name>, or type ffd)");
    const io::FoamDictionary& d = e.dict();
    if (d.found("type") && d.get<std::string>("type") == "ffd")
        return read_lattice_variables(e, out);
    if (d.found("handle") == d.found("patches"))
        throw e.error("give exactly one of patches (...) or handle <name>");
    DesignVariable v = d.found("handle") ? read_handle_variable(e) : read_patch_variable(e);
    v.name = e.keyword();
    v.line = e.line();
    out.variables.push_back(std::move(v));
}

} // namespace

bool DesignLattice::belongs(Index p, const std::array<int, 3>& ijk) const
{
    const std::array<int, 3>& n = lattice.counts();
    const std::array<int, 3> at{int(p % n[0]), int((p / n[0]) % n[1]), int(p / (n[0] * n[1]))};
    for (int a = 0; a < 3; ++a)
        if (counts[std::size_t(a)] > 1 && at[std::size_t(a)] != ijk[std::size_t(a)])
            return false;
    return true;
}

Index DesignVariables::find(const std::string& name) const
{
    for (std::size_t i = 0; i < variables.size(); ++i)
        if (variables[i].name == name)
            return Index(i);
    return -1;
}

bool DesignVariables::reads_point_displacement() const
{
    return std::any_of(variables.begin(), variables.end(),
                       [](const DesignVariable& v)
                       {
                           return v.kind == DesignVariable::Kind::patches &&
                                  v.motion.type == MotionType::point_displacement;
                       });
}

DesignVariables read_design_variables(const io::FoamDictionary& dict)
{
    DesignVariables out;
    out.dict_path = dict.path();
    const io::FoamDictionary* d = dict.find_dict("designVariables");
    if (d == nullptr)
        return out;
    for (const io::FoamEntry& e : d->entries())
    {
        if (e.is_regex())
            throw e.error("a design variable's name is a plain word, not a regex");
        read_variable(e, out);
    }
    std::set<std::string> names;
    for (const DesignVariable& v : out.variables)
        if (!names.insert(v.name).second)
            throw dict.entry("designVariables")
                .error("design variable '" + v.name + "' is defined twice");
    if (out.variables.empty())
        throw dict.entry("designVariables")
            .error("no design variables (a lattice whose "
                   "control points are all confined?)");
    return out;
}

} // namespace meshmorph::design
