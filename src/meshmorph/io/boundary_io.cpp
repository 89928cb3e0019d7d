// SPDX-License-Identifier: GPL-3.0-or-later
// polyMesh boundary and zone files: patch/zone lists of small dictionaries.
#include "meshmorph/io/boundary_io.h"

#include <cstring>
#include <limits>

#include "meshmorph/io/foam_dictionary.h"

namespace meshmorph::io
{

namespace
{

Index to_index(const FoamEntry& e, std::int64_t v, const std::string& what)
{
    if (v < 0)
        throw e.error(what + " must not be negative (found " + std::to_string(v) + ")");
    if (v > static_cast<std::int64_t>(std::numeric_limits<Index>::max()))
        throw e.error(what + " " + std::to_string(v) +
                      " does not fit the label size of this "
                      "build (configure with MESHMORPH_LABEL64=ON)");
    return static_cast<Index>(v);
}

std::string read_list_name(FoamTokenizer& tok, const std::string& file_kind, std::int64_t n,
                           std::int64_t i)
{
    FoamToken name = tok.next();
    if (name.is_punct(')') || name.is_end())
        throw tok.error_at(name.line, file_kind + " declares " + std::to_string(n) +
                                          " entries but has only " + std::to_string(i));
    if (!name.is_word() && !name.is_string())
        throw tok.error_at(name.line,
                           "expected a " + file_kind + " entry name but found " + name.describe());
    return std::move(name.text);
}

void close_list(FoamTokenizer& tok, const std::string& file_kind, std::int64_t n)
{
    const FoamToken close = tok.next();
    if (!close.is_punct(')'))
        throw tok.error_at(close.line, file_kind + " declares " + std::to_string(n) +
                                           " entries but has more (found " + close.describe() +
                                           " where ')' was expected)");
}

// Zone label lists: `List<label> N(...)`, `N(...)`, binary blocks, and the bare `0` that
// OpenFOAM writes for an empty list in binary files.
std::vector<Index> zone_labels(const FoamEntry& e, const std::string& what)
{
    const auto& t = e.tokens();
    std::vector<std::int64_t> wide;
    if (t.size() == 1 && t[0].is_label() && t[0].label == 0)
        return {};
    wide = e.get<std::vector<std::int64_t>>();
    std::vector<Index> out(wide.size());
    for (std::size_t i = 0; i < wide.size(); ++i)
        out[i] = to_index(e, wide[i], what + " element " + std::to_string(i));
    return out;
}

void write_keyword(std::string& out, const std::string& indent, const std::string& key,
                   const std::string& value)
{
    out += indent;
    out += key;
    if (!value.empty() && value.front() == '{')
    {
        // A verbatim sub-dictionary: OpenFOAM puts its braces on their own lines.
        out += "\n" + indent + value + "\n";
        return;
    }
    // OpenFOAM's writeKeyword pads keywords to 16 columns (at least one space).
    out.append(key.size() < 16 ? 16 - key.size() : 1, ' ');
    out += value;
    out += ";\n";
}

std::string labels_keyword(const std::string& type)
{
    if (type == "cellZone")
        return "cellLabels";
    if (type == "faceZone")
        return "faceLabels";
    if (type == "pointZone")
        return "pointLabels";
    throw InvalidInput("unknown zone type '" + type +
                       "' (expected cellZone, faceZone or pointZone)");
}

// One label/bool list entry as OpenFOAM v1912 writes it in a zone file.
template <class T>
void write_zone_list(std::string& out, const std::string& key, const std::string& type_word,
                     const std::vector<T>& values, FoamFormat format, int label_bytes, bool is_bool)
{
    const std::size_t n = values.size();
    out += key;
    out.append(key.size() < 16 ? 16 - key.size() : 1, ' ');
    if (n == 0)
    {
        out += format == FoamFormat::binary ? "0;\n" : "0();\n";
        return;
    }
    out += type_word;
    if (format == FoamFormat::binary)
    {
        out += " \n" + std::to_string(n) + "\n(";
        for (const T& v : values)
        {
            if (is_bool)
                out.push_back(v ? '\1' : '\0');
            else if (label_bytes == 4)
            {
                const std::int32_t x = static_cast<std::int32_t>(v);
                char b[4];
                std::memcpy(b, &x, 4);
                out.append(b, 4);
            }
            else
            {
                const std::int64_t x = static_cast<std::int64_t>(v);
                char b[8];
                std::memcpy(b, &x, 8);
                out.append(b, 8);
            }
        }
        out += ");\n";
        return;
    }
    const auto item = [&](const T& v)
    { return is_bool ? std::string(v ? "1" : "0") : std::to_string(static_cast<std::int64_t>(v)); };
    bool uniform = n > 1;
    for (std::size_t i = 1; i < n && uniform; ++i)
        uniform = (values[i] != 0) == (values[0] != 0) && (is_bool || values[i] == values[0]);
    if (uniform)
    {
        out += " " + std::to_string(n) + "{" + item(values[0]) + "};\n";
        return;
    }
    if (n <= 10)
    {
        out += " " + std::to_string(n) + "(";
        for (std::size_t i = 0; i < n; ++i)
        {
            if (i)
                out += ' ';
            out += item(values[i]);
        }
        out += ");\n";
        return;
    }
    out += " \n" + std::to_string(n) + "\n(\n";
    for (const T& v : values)
    {
        out += item(v);
        out += '\n';
    }
    out += ")\n;\n";
}

} // namespace

namespace
{

//! One patch entry of a boundary file, after its name: `{ type ..; nFaces ..; startFace ..; }`.
Patch read_patch(FoamTokenizer& tok, std::string name)
{
    Patch p;
    p.name = std::move(name);
    const FoamDictionary d = parse_dictionary_block(tok, p.name);
    bool has_type = false, has_n = false, has_start = false;
    for (const FoamEntry& e : d.entries())
    {
        const std::string& k = e.keyword();
        if (k == "type")
        {
            p.type = e.get<std::string>();
            has_type = true;
        }
        else if (k == "nFaces")
        {
            p.n_faces = to_index(e, e.get<std::int64_t>(), "nFaces");
            has_n = true;
        }
        else if (k == "startFace")
        {
            p.start_face = to_index(e, e.get<std::int64_t>(), "startFace");
            has_start = true;
        }
        else
        {
            if (k == "inGroups")
                p.in_groups = e.get<std::vector<std::string>>();
            p.entries.emplace_back(k, e.source_text());
        }
    }
    const auto missing = [&](const char* key)
    { return tok.error_at(d.line(), "patch '" + p.name + "' has no '" + key + "' entry"); };
    if (!has_type)
        throw missing("type");
    if (!has_n)
        throw missing("nFaces");
    if (!has_start)
        throw missing("startFace");
    return p;
}

} // namespace

std::vector<Patch> parse_boundary(FoamTokenizer& tok)
{
    std::vector<Patch> patches;
    if (tok.peek_char() == '(')
    {
        // A list without its size, as OpenFOAM also reads (driftFluxFoam's tank3D ships one).
        tok.expect('(');
        for (FoamToken name = tok.next(); !name.is_punct(')'); name = tok.next())
        {
            if (name.is_end())
                throw tok.error_at(name.line, "boundary list is not closed by ')'");
            if (!name.is_word() && !name.is_string())
                throw tok.error_at(name.line,
                                   "expected a boundary entry name but found " + name.describe());
            patches.push_back(read_patch(tok, std::move(name.text)));
        }
        return patches;
    }
    const std::int64_t n = tok.expect_size("the number of patches");
    tok.expect('(');
    patches.reserve(static_cast<std::size_t>(std::min<std::int64_t>(n, 1 << 16)));
    for (std::int64_t i = 0; i < n; ++i)
        patches.push_back(read_patch(tok, read_list_name(tok, "boundary", n, i)));
    close_list(tok, "boundary", n);
    return patches;
}

std::vector<Patch> parse_boundary(std::string_view text, const std::string& path)
{
    FoamTokenizer tok(text, path);
    if (has_header(tok))
        parse_header(tok);
    std::vector<Patch> patches = parse_boundary(tok);
    if (!tok.at_end())
        throw tok.error_at(tok.peek().line,
                           "unexpected " + tok.peek().describe() + " after the patch list");
    return patches;
}

std::vector<Zone> parse_zones(FoamTokenizer& tok, const FoamHeader& header)
{
    ParseOptions options;
    options.binary = header.is_binary();
    options.label_bytes = header.label_bytes;
    options.scalar_bytes = header.scalar_bytes;
    const std::int64_t n = tok.expect_size("the number of zones");
    tok.expect('(');
    std::vector<Zone> zones;
    for (std::int64_t i = 0; i < n; ++i)
    {
        Zone z;
        z.name = read_list_name(tok, "zone list", n, i);
        const FoamDictionary d = parse_dictionary_block(tok, z.name, options);
        bool has_type = false;
        const FoamEntry* flip = nullptr;
        for (const FoamEntry& e : d.entries())
        {
            const std::string& k = e.keyword();
            if (k == "type")
            {
                z.type = e.get<std::string>();
                has_type = true;
            }
            else if (k == "cellLabels" || k == "faceLabels" || k == "pointLabels")
            {
                z.labels = zone_labels(e, k);
            }
            else if (k == "flipMap")
            {
                const std::vector<Index> f = zone_labels(e, k);
                z.flip_map.assign(f.begin(), f.end());
                for (std::size_t j = 0; j < f.size(); ++j)
                    if (f[j] > 1)
                        throw e.error("flipMap element " + std::to_string(j) +
                                      " is not a bool (0 or 1)");
                flip = &e;
            }
            else
                z.entries.emplace_back(k, e.source_text());
        }
        if (!has_type)
            throw tok.error_at(d.line(), "zone '" + z.name + "' has no 'type' entry");
        if (flip && z.flip_map.size() != z.labels.size())
            throw flip->error("flipMap has " + std::to_string(z.flip_map.size()) +
                              " elements but the zone has " + std::to_string(z.labels.size()) +
                              " faces");
        zones.push_back(std::move(z));
    }
    close_list(tok, "zone list", n);
    return zones;
}

std::vector<Zone> parse_zones(std::string_view text, const std::string& path)
{
    FoamTokenizer tok(text, path);
    const FoamHeader header = parse_header(tok);
    std::vector<Zone> zones = parse_zones(tok, header);
    if (!tok.at_end())
        throw tok.error_at(tok.peek().line,
                           "unexpected " + tok.peek().describe() + " after the zone list");
    return zones;
}

std::string format_boundary(const std::vector<Patch>& patches)
{
    std::string out = std::to_string(patches.size()) + "\n(\n";
    const std::string indent = "        ";
    for (const Patch& p : patches)
    {
        out += "    " + p.name + "\n    {\n";
        write_keyword(out, indent, "type", p.type);
        bool has_groups = false;
        for (const auto& [k, v] : p.entries)
            if (k == "physicalType" || k == "inGroups")
            {
                write_keyword(out, indent, k, v);
                has_groups = has_groups || k == "inGroups";
            }
        if (!has_groups && !p.in_groups.empty())
        {
            std::string v = std::to_string(p.in_groups.size()) + "(";
            for (std::size_t i = 0; i < p.in_groups.size(); ++i)
                v += (i ? " " : "") + p.in_groups[i];
            write_keyword(out, indent, "inGroups", v + ")");
        }
        write_keyword(out, indent, "nFaces", std::to_string(p.n_faces));
        write_keyword(out, indent, "startFace", std::to_string(p.start_face));
        for (const auto& [k, v] : p.entries)
            if (k != "physicalType" && k != "inGroups")
                write_keyword(out, indent, k, v);
        out += "    }\n";
    }
    out += ")";
    return out;
}

std::string format_zones(const std::vector<Zone>& zones, FoamFormat format, int label_bytes)
{
    if (format == FoamFormat::binary && label_bytes != 4 && label_bytes != 8)
        throw InvalidInput("format_zones: label_bytes must be 4 or 8, not " +
                           std::to_string(label_bytes));
    std::string out = std::to_string(zones.size()) + "\n(\n";
    for (std::size_t i = 0; i < zones.size(); ++i)
    {
        const Zone& z = zones[i];
        const std::string key = labels_keyword(z.type);
        if (z.type == "faceZone" && z.flip_map.size() != z.labels.size())
            throw InvalidInput("format_zones: zone '" + z.name + "' has " +
                               std::to_string(z.labels.size()) + " faces but " +
                               std::to_string(z.flip_map.size()) + " flipMap entries");
        if (i)
            out += "\n";
        out += z.name + "\n{\n    type " + z.type + ";\n";
        write_zone_list(out, key, "List<label>", z.labels, format, label_bytes, false);
        if (z.type == "faceZone")
            write_zone_list(out, "flipMap", "List<bool>", z.flip_map, format, label_bytes, true);
        for (const auto& [k, v] : z.entries)
            write_keyword(out, "", k, v);
        out += "}\n";
    }
    out += ")";
    return out;
}

} // namespace meshmorph::io
