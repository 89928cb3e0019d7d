// SPDX-License-Identifier: GPL-3.0-or-later
// morphDict deformation settings: one reader per sub-dictionary.
#include "meshmorph/morph/deformation_dict.h"

#include <algorithm>
#include <limits>
#include <sstream>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/memory_budget.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/morph/deformation_methods.h"
#include "meshmorph/morph/fit_memory.h"

namespace meshmorph::morph
{

namespace
{

SizeEntry size_entry(const io::FoamEntry& e, const std::string& name)
{
    return {e.path(), e.line(), name};
}

//! Expect punctuation c at tokens[i] and advance.
void expect_punct(const io::FoamEntry& e, const std::vector<io::FoamValueToken>& t, std::size_t& i,
                  char c)
{
    if (i >= t.size() || !t[i].is_punct(c))
        throw e.error(std::string("expected '") + c +
                      "' in a list of ((i j k) (dx dy dz)), found " +
                      (i < t.size() ? t[i].describe() : std::string("end of entry")));
    ++i;
}

double number(const io::FoamEntry& e, const std::vector<io::FoamValueToken>& t, std::size_t& i)
{
    if (i >= t.size() || !t[i].is_number())
        throw e.error("expected a number in a list of ((i j k) (dx dy dz)), found " +
                      (i < t.size() ? t[i].describe() : std::string("end of entry")));
    return t[i++].scalar;
}

//! `displacements ( ((i j k) (dx dy dz)) ... );` (an optional count before the list).
std::vector<ControlDisplacement> read_control_displacements(const io::FoamEntry& e,
                                                            const std::array<int, 3>& counts)
{
    const std::vector<io::FoamValueToken>& t = e.tokens();
    std::size_t i = 0;
    if (i < t.size() && t[i].is_label())
        ++i;
    expect_punct(e, t, i, '(');
    std::vector<ControlDisplacement> out;
    while (i < t.size() && !t[i].is_punct(')'))
    {
        ControlDisplacement c;
        expect_punct(e, t, i, '(');
        expect_punct(e, t, i, '(');
        for (int a = 0; a < 3; ++a)
        {
            if (i >= t.size() || !t[i].is_label())
                throw e.error("control point index must be an integer, found " +
                              (i < t.size() ? t[i].describe() : std::string("end of entry")));
            const std::int64_t v = t[i++].label;
            if (v < 0 || v >= counts[a])
                throw e.error("control point index " + std::to_string(v) + " out of range [0, " +
                              std::to_string(counts[a] - 1) + "]");
            c.index[a] = static_cast<int>(v);
        }
        expect_punct(e, t, i, ')');
        expect_punct(e, t, i, '(');
        for (int a = 0; a < 3; ++a)
            c.displacement[a] = number(e, t, i);
        expect_punct(e, t, i, ')');
        expect_punct(e, t, i, ')');
        out.push_back(c);
    }
    expect_punct(e, t, i, ')');
    if (i != t.size())
        throw e.error("unexpected " + t[i].describe() + " after the list");
    return out;
}

//! `idw { exponents (3 5); alpha 0.2; theta 0.2; }`
IdwSettings read_idw_settings(const io::FoamDictionary& d)
{
    d.check_keywords({"exponents", "alpha", "theta"}, "idw");
    IdwSettings s;
    if (const io::FoamEntry* e = d.find("exponents"))
    {
        const std::vector<std::int32_t> ab = e->get<std::vector<std::int32_t>>();
        if (ab.size() != 2 || ab[0] < 1 || ab[1] <= ab[0] || ab[1] > 12)
            throw e->error("expected (a b) with 1 <= a < b <= 12, e.g. (3 5)");
        s.far_exponent = ab[0];
        s.near_exponent = ab[1];
    }
    s.alpha = d.get_or<double>("alpha", s.alpha);
    if (!(s.alpha > 0.0))
        throw d.entry("alpha").error("alpha must be > 0");
    s.theta = d.get_or<double>("theta", s.theta);
    if (!(s.theta >= 0.0 && s.theta <= 0.7))
        throw d.entry("theta").error("theta must be in [0, 0.7] (0: direct sum)");
    return s;
}

//! A value from a list of names (kernel, method), the error naming the entry.
template <class Parse> auto parse_named(const io::FoamEntry& e, Parse parse)
{
    try
    {
        return parse(e.get<std::string>());
    }
    catch (const InvalidInput& err)
    {
        throw e.error(err.what());
    }
}

//! `rbf { greedy { tolerance ...; maxCentres ...; ... } }`: each key alone (an unset key
//! keeps its default; rmsTolerance unset: no RMS criterion beyond the max one).
GreedySettings read_greedy_settings(const io::FoamDictionary& g, SizeEntry& centres_entry)
{
    g.check_keywords({"tolerance", "rmsTolerance", "maxCentres", "initialCentres", "batchSize",
                      "spread", "jumpSlope", "jumpWidth"},
                     "rbf.greedy");
    GreedySettings gs;
    gs.tolerance = g.get_or<double>("tolerance", gs.tolerance);
    gs.rms_tolerance = g.get_or<double>("rmsTolerance", gs.tolerance);
    gs.max_centres = g.get_or<std::int32_t>("maxCentres", gs.max_centres);
    gs.initial_centres = g.get_or<std::int32_t>("initialCentres", gs.initial_centres);
    gs.batch_size = g.get_or<std::int32_t>("batchSize", gs.batch_size);
    gs.spread = g.get_or<double>("spread", gs.spread);
    gs.jump_slope = g.get_or<double>("jumpSlope", gs.jump_slope);
    gs.jump_width = g.get_or<double>("jumpWidth", gs.jump_width);
    for (const char* key : {"spread", "jumpSlope", "jumpWidth"})
        if (const io::FoamEntry* e = g.find(key); e && !(e->get<double>() >= 0.0))
            throw e->error(std::string(key) + " must be >= 0 (0: off)");
    if (!(gs.tolerance > 0.0))
        throw g.entry("tolerance").error("tolerance must be > 0");
    if (gs.max_centres < 1)
        throw g.entry("maxCentres").error("maxCentres must be >= 1");
    if (const io::FoamEntry* e = g.find("maxCentres"))
        centres_entry = size_entry(*e, "rbf.greedy.maxCentres");
    return gs;
}

//! `rbf { kernel ...; shape ...; polynomial linear|none; supportRadius ...; order ...;
//! greedy { ... } }`
void read_rbf_settings(const io::FoamDictionary& d, DeformationSettings& s)
{
    d.check_keywords({"kernel", "shape", "polynomial", "supportRadius", "order", "greedy", "limit"},
                     "rbf");
    s.limit = d.get_or<bool>("limit", s.limit);
    if (const io::FoamEntry* e = d.find("kernel"))
        s.rbf.kernel = parse_named(*e, rbf_kernel_from_string);
    s.rbf.shape_parameter = d.get_or<double>("shape", s.rbf.shape_parameter);
    if (!(s.rbf.shape_parameter > 0.0))
        throw d.entry("shape").error("shape must be > 0");
    s.rbf.support_radius = d.get_or<double>("supportRadius", s.rbf.support_radius);
    s.rbf.polyharmonic_order = d.get_or<std::int32_t>("order", s.rbf.polyharmonic_order);
    if (const io::FoamEntry* e = d.find("polynomial"))
    {
        const std::string p = e->get<std::string>();
        if (p != "linear" && p != "none")
            throw e->error("unknown polynomial '" + p + "' (valid: linear none)");
        s.rbf.polynomial = p == "linear";
    }
    if (d.found("greedy"))
        s.greedy = read_greedy_settings(d.sub_dict("greedy"), s.greedy_centres);
}

//! `dmffd { lattice (nx ny nz); clamping ...; bounds (...); }`
void read_dmffd_settings(const io::FoamDictionary& d, DeformationSettings& s)
{
    d.check_keywords({"lattice", "clamping", "bounds"}, "dmffd");
    if (d.found("lattice"))
    {
        s.dmffd.lattice.control_points = read_lattice(d);
        s.dmffd_lattice = size_entry(d.entry("lattice"), "dmffd.lattice");
    }
    s.dmffd.clamping = d.get_or<double>("clamping", s.dmffd.clamping);
    if (!(s.dmffd.clamping >= 0.0 && s.dmffd.clamping < 1.0))
        throw d.entry("clamping").error("clamping must be in [0, 1)");
    s.dmffd.lattice.box = read_bounds(d);
}

//! `ffd { lattice (nx ny nz); bounds (...); displacements ( ((i j k) (dx dy dz)) ... ); }`
void read_ffd_settings(const io::FoamDictionary& d, DeformationSettings& s)
{
    d.check_keywords({"lattice", "bounds", "displacements"}, "ffd");
    if (d.found("lattice"))
        s.ffd.control_points = read_lattice(d);
    s.ffd.box = read_bounds(d);
    if (const io::FoamEntry* e = d.find("displacements"))
        s.ffd_displacements = read_control_displacements(*e, s.ffd.control_points);
}

//! FFD moves control points; without `displacements` it would move nothing.
void require_ffd_displacements(const io::FoamDictionary& dict)
{
    const io::FoamDictionary* d = dict.find_dict("ffd");
    if (d == nullptr || !d->found("displacements"))
        throw ParseError(dict.path(), d ? d->line() : 0,
                         "method ffd needs ffd { lattice (nx ny nz); displacements ( ((i j k) "
                         "(dx dy dz)) ... ); }: FFD moves control points, it does not fit the "
                         "boundary prescriptions");
}

} // namespace

std::array<int, 3> read_lattice(const io::FoamDictionary& d)
{
    const io::FoamEntry& e = d.entry("lattice");
    const std::vector<std::int32_t> n = e.get<std::vector<std::int32_t>>();
    if (n.size() != 3)
        throw e.error("expected three control-point counts (nx ny nz)");
    for (std::int32_t v : n)
        if (v < 4)
            throw e.error("a cubic B-spline lattice needs at least 4 control points per "
                          "direction, got " +
                          std::to_string(v));
    // Checked before anything is sized by it: the count overflows a label long before a
    // lattice stops fitting in memory.
    const double count = double(n[0]) * double(n[1]) * double(n[2]);
    if (count > double(std::numeric_limits<Index>::max()))
        throw e.error(format_count(count) + " control points, more than a label counts");
    if (const std::optional<std::string> shortfall = memory_shortfall(ffd_lattice_bytes(count)))
        throw e.error(format_count(count) + " control points " + *shortfall);
    return {n[0], n[1], n[2]};
}

std::optional<FfdBox> read_bounds(const io::FoamDictionary& d, const std::string& key)
{
    const io::FoamEntry* e = d.find(key);
    if (e == nullptr)
        return std::nullopt;
    const std::vector<Vector3> corners = e->get<std::vector<Vector3>>();
    if (corners.size() != 2)
        throw e->error("expected ((x0 y0 z0) (x1 y1 z1))");
    const Vector3 extent = corners[1] - corners[0];
    if ((extent.array() <= 0.0).any())
        throw e->error(key + ": the second corner must exceed the first in x, y and z");
    FfdBox box;
    box.origin = corners[0];
    box.axes = extent.asDiagonal();
    return box;
}

DeformationSettings read_deformation_settings(const io::FoamDictionary& dict,
                                              const std::optional<std::string>& method_override)
{
    DeformationSettings s;
    if (method_override)
        s.method = deformation_method_from_string(*method_override);
    else if (const io::FoamEntry* e = dict.find("method"))
        s.method = parse_named(*e, deformation_method_from_string);
    // Every method's sub-dictionary present is validated (a typo in an unused one is still
    // a mistake the user wants to hear about); the chosen one is used.
    if (const io::FoamDictionary* d = dict.find_dict("rbf"))
        read_rbf_settings(*d, s);
    if (const io::FoamDictionary* d = dict.find_dict("idw"))
        s.idw = read_idw_settings(*d);
    if (const io::FoamDictionary* d = dict.find_dict("dmffd"))
        read_dmffd_settings(*d, s);
    if (const io::FoamDictionary* d = dict.find_dict("ffd"))
        read_ffd_settings(*d, s);
    if (s.method == DeformationMethod::ffd)
        require_ffd_displacements(dict);
    return s;
}

} // namespace meshmorph::morph
