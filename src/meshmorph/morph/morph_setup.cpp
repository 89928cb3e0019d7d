// SPDX-License-Identifier: GPL-3.0-or-later
// The morphDict's boundary entries, handles and conflict rule, read and checked.
#include "meshmorph/morph/morph_setup.h"

#include <array>
#include <cmath>
#include <tuple>
#include <type_traits>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_dictionary.h"

namespace meshmorph::morph
{

namespace
{

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

//! `type <word>;` of a boundary entry. empty and wedge are the patch's own type, not a motion.
MotionType read_motion_type(const io::FoamDictionary& d)
{
    const io::FoamEntry& type_entry = d.entry("type");
    const std::string type = type_entry.get<std::string>();
    if (type == "empty" || type == "wedge")
        throw type_entry.error("type " + type + " is implied by the patch type; remove the entry");
    try
    {
        return motion_type_from_string(type);
    }
    catch (const InvalidInput& err)
    {
        throw type_entry.error(err.what());
    }
}

//! `factor s;` (uniform) or `factor (sx sy sz);`.
Vector3 read_scale_factor(const io::FoamEntry& f)
{
    if (f.tokens().size() == 1)
        return Vector3::Constant(f.get<double>());
    return f.get<Vector3>();
}

//! `value`, or an error naming the keyword `key` of `d` (its line) when it is not finite.
template <class T> T finite(const io::FoamDictionary& d, const std::string& key, const T& value)
{
    bool ok = false;
    if constexpr (std::is_same_v<T, double>)
        ok = std::isfinite(value);
    else
        ok = value.allFinite();
    if (!ok)
        throw d.entry(key).error("not a finite number (NaN or inf)");
    return value;
}

template <class T> T get_finite(const io::FoamDictionary& d, const std::string& key)
{
    return finite<T>(d, key, d.get<T>(key));
}

//! The parameters of `m.type` from its entry (keywords checked first; `other` are allowed
//! besides the type's own).
void read_motion_parameters(const io::FoamDictionary& d, Motion& m,
                            const std::vector<std::string>& other = {})
{
    std::vector<std::string> allowed = motion_keywords(m.type);
    allowed.push_back("type");
    allowed.insert(allowed.end(), other.begin(), other.end());
    d.check_keywords(allowed, "type " + to_string(m.type));
    switch (m.type)
    {
    case MotionType::translate:
        m.vector = get_finite<Vector3>(d, "vector");
        break;
    case MotionType::rotate:
        m.origin = get_finite<Vector3>(d, "origin");
        m.axis = get_finite<Vector3>(d, "axis");
        m.angle_degrees = get_finite<double>(d, "angle");
        if (m.axis.norm() == 0.0)
            throw d.entry("axis").error("rotation axis must not be zero");
        break;
    case MotionType::scale:
        m.origin = get_finite<Vector3>(d, "origin");
        m.factor = finite<Vector3>(d, "factor", read_scale_factor(d.entry("factor")));
        break;
    case MotionType::surface:
        m.file = d.get<std::string>("file");
        break;
    default:
        break;
    }
}

bool is_finite(const Motion& m)
{
    return m.vector.allFinite() && m.origin.allFinite() && m.axis.allFinite() &&
           m.factor.allFinite() && std::isfinite(m.angle_degrees);
}

BoundaryEntry read_boundary_entry(const io::FoamEntry& e)
{
    if (!e.is_dict())
        throw e.error("expected a sub-dictionary { type <fixed|translate|...>; ... }");
    BoundaryEntry entry;
    entry.key = e.keyword();
    entry.is_regex = e.is_regex();
    entry.line = e.line();
    entry.motion = read_motion(e);
    return entry;
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

//! `points ((x y z) ...);` as a k x 3 matrix.
Points read_handle_positions(const io::FoamEntry& e)
{
    const std::vector<Vector3> pts = e.get<std::vector<Vector3>>();
    if (pts.empty())
        throw e.error("empty list");
    Points out(static_cast<Eigen::Index>(pts.size()), 3);
    for (std::size_t i = 0; i < pts.size(); ++i)
        out.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
    return out;
}

//! The one selection of a handle: pointZone, box or points.
void read_handle_selection(const io::FoamEntry& e, HandleEntry& h)
{
    const io::FoamDictionary& d = e.dict();
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
        h.points = read_handle_positions(d.entry("points"));
    }
}

HandleEntry read_handle_entry(const io::FoamEntry& e)
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
    read_handle_selection(e, h);
    return h;
}

ConflictRule read_conflict_rule(const io::FoamEntry& e)
{
    try
    {
        return conflict_rule_from_string(e.get<std::string>());
    }
    catch (const InvalidInput& err)
    {
        throw e.error(err.what());
    }
}

} // namespace

Motion read_motion(const io::FoamEntry& e, const std::vector<std::string>& other_keywords)
{
    Motion motion;
    motion.type = read_motion_type(e.dict());
    read_motion_parameters(e.dict(), motion, other_keywords);
    if (!is_finite(motion))
        throw e.error("non-finite value");
    return motion;
}

namespace
{

//! `jumpSmoothing auto | <switch>` (absent: auto).
JumpSmoothingMode read_jump_smoothing(const io::FoamDictionary& dict)
{
    const io::FoamEntry* e = dict.find("jumpSmoothing");
    if (e == nullptr)
        return JumpSmoothingMode::automatic;
    const std::vector<io::FoamValueToken>& t = e->tokens();
    if (t.size() == 1 && t[0].is_word("auto"))
        return JumpSmoothingMode::automatic;
    try
    {
        return dict.get<bool>("jumpSmoothing") ? JumpSmoothingMode::on : JumpSmoothingMode::off;
    }
    catch (const ParseError&)
    {
        throw e->error("expected auto, yes or no (or another switch: on/off, true/false) but "
                       "found '" +
                       (t.empty() ? std::string() : t[0].text) + "'");
    }
}

} // namespace

MorphSetup read_morph_setup(const io::FoamDictionary& dict)
{
    MorphSetup setup;
    setup.dict_path = dict.path();
    // Other top-level entries are allowed when used as $variables (helper entries).
    dict.check_keywords({"method", "rbf", "dmffd", "ffd", "idw", "steps", "untangle",
                         "maxUntangleCells", "boundary", "handles", "conflicts", "designVariables",
                         "newCheckFailures", "jumpSmoothing", "designBasis", "maxNonOrtho"},
                        "morphDict", dict.referenced_variables());
    if (const io::FoamEntry* e = dict.find("conflicts"))
        setup.conflicts = read_conflict_rule(*e);
    setup.jump_smoothing = read_jump_smoothing(dict);
    if (dict.found("boundary"))
        for (const io::FoamEntry& e : dict.sub_dict("boundary").entries())
            setup.boundary.push_back(read_boundary_entry(e));
    if (dict.found("handles"))
        for (const io::FoamEntry& e : dict.sub_dict("handles").entries())
            setup.handles.push_back(read_handle_entry(e));
    return setup;
}

} // namespace meshmorph::morph
