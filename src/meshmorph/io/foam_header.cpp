// SPDX-License-Identifier: GPL-3.0-or-later
// The FoamFile header: parsing with clear errors, and writing it as OpenFOAM v1912 does.
#include "meshmorph/io/foam_header.h"

#include <optional>
#include <string_view>
#include <vector>

namespace meshmorph::io
{

namespace
{

// Banner and dividers copied byte for byte from files written by OpenFOAM v1912 (Debian
// build, whose banner carries an empty version string). The banner's first and last lines
// also frame the text of framed_banner.
constexpr const char* banner_top =
    "/*--------------------------------*- C++ -*----------------------------------*\\\n";
constexpr const char* banner_bottom =
    "\\*---------------------------------------------------------------------------*/\n";
constexpr const char* banner_body =
    "| =========                 |                                                 |\n"
    "| \\\\      /  F ield         | OpenFOAM: The Open Source CFD Toolbox           |\n"
    "|  \\\\    /   O peration     | Version:                                        |\n"
    "|   \\\\  /    A nd           | Website:  www.openfoam.com                      |\n"
    "|    \\\\/     M anipulation  |                                                 |\n";
constexpr const char* divider =
    "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n";
constexpr const char* end_divider =
    "// ************************************************************************* //\n";

void write_entry(std::string& out, const std::string& key, const std::string& value)
{
    // OpenFOAM's writeKeyword pads header keywords to 12 columns after a 4-space indent.
    out += "    ";
    out += key;
    out.append(key.size() < 12 ? 12 - key.size() : 1, ' ');
    out += value;
    out += ";\n";
}

// Which `FoamFile` entries parse_header has seen.
struct HeaderEntriesSeen
{
    bool format = false;
    bool class_name = false;
    std::size_t arch_line = 0;
};

// `FoamFile {`; returns the line of `FoamFile`.
std::size_t read_header_open(FoamTokenizer& tokenizer)
{
    const FoamToken first = tokenizer.next();
    if (!first.is_word("FoamFile"))
        throw tokenizer.error_at(first.line == 0 ? tokenizer.line() : first.line,
                                 "expected the 'FoamFile' header but found " + first.describe());
    tokenizer.expect('{');
    return first.line;
}

// The keyword of the next header entry, or nullopt at the closing `}`.
std::optional<FoamToken> read_header_key(FoamTokenizer& tokenizer, const FoamHeader& header)
{
    FoamToken key = tokenizer.next();
    if (key.is_punct('}'))
        return std::nullopt;
    if (key.is_end())
        throw tokenizer.error_at(header.line, "unterminated 'FoamFile' header (no closing '}')");
    if (!key.is_word())
        throw tokenizer.error_at(
            key.line, "expected a keyword in the 'FoamFile' header but found " + key.describe());
    return key;
}

// The value tokens of entry `key`, up to its `;`.
std::vector<FoamToken> read_header_value(FoamTokenizer& tokenizer, const FoamToken& key)
{
    std::vector<FoamToken> value;
    for (;;)
    {
        FoamToken t = tokenizer.next();
        if (t.is_punct(';'))
            return value;
        if (t.is_end() || t.is_punct('}') || t.is_punct('{'))
            throw tokenizer.error_at(t.line, "expected ';' after 'FoamFile' entry '" + key.text +
                                                 "' but found " + t.describe());
        value.push_back(std::move(t));
    }
}

const std::string& single_value(const FoamTokenizer& tokenizer, const FoamToken& key,
                                const std::vector<FoamToken>& value)
{
    if (value.size() != 1)
        throw tokenizer.error_at(key.line,
                                 "'FoamFile' entry '" + key.text + "' must have exactly one value");
    return value.front().text;
}

FoamFormat parse_format(const FoamTokenizer& tokenizer, const FoamToken& key, const std::string& f)
{
    if (f == "ascii")
        return FoamFormat::ascii;
    if (f == "binary")
        return FoamFormat::binary;
    throw tokenizer.error_at(key.line, "unknown format '" + f +
                                           "' in 'FoamFile' header (expected ascii "
                                           "or binary)");
}

// Stores entry `key` in `header`. Unknown keys are ignored, as OpenFOAM does.
void set_header_entry(const FoamTokenizer& tokenizer, const FoamToken& key,
                      const std::vector<FoamToken>& value, FoamHeader& header,
                      HeaderEntriesSeen& seen)
{
    const auto single = [&]() -> const std::string& { return single_value(tokenizer, key, value); };
    if (key.text == "version")
        header.version = single();
    else if (key.text == "format")
    {
        header.format = parse_format(tokenizer, key, single());
        seen.format = true;
    }
    else if (key.text == "class")
    {
        header.class_name = single();
        seen.class_name = true;
    }
    else if (key.text == "object")
        header.object = single();
    else if (key.text == "location")
        header.location = single();
    else if (key.text == "note")
        header.note = single();
    else if (key.text == "arch")
    {
        header.arch = single();
        seen.arch_line = key.line;
    }
}

void check_required_entries(const FoamTokenizer& tokenizer, const FoamHeader& header,
                            const HeaderEntriesSeen& seen, bool require_format_and_class)
{
    if (!seen.format && require_format_and_class)
        throw tokenizer.error_at(header.line, "'FoamFile' header has no 'format' entry");
    if (!seen.class_name && require_format_and_class)
        throw tokenizer.error_at(header.line, "'FoamFile' header has no 'class' entry");
}

} // namespace

bool has_header(FoamTokenizer& tokenizer)
{
    return tokenizer.peek().is_word("FoamFile");
}

void parse_arch(const std::string& arch, FoamHeader& header, const std::string& path,
                std::size_t line)
{
    std::size_t begin = 0;
    while (begin <= arch.size())
    {
        std::size_t end = arch.find(';', begin);
        if (end == std::string::npos)
            end = arch.size();
        const std::string part = arch.substr(begin, end - begin);
        if (part == "MSB")
            throw ParseError(path, line,
                             "big-endian (MSB) binary data is not supported (arch \"" + arch +
                                 "\")");
        const auto parse_size = [&](const std::string& prefix, int& bytes)
        {
            if (part.rfind(prefix, 0) != 0)
                return false;
            const std::string bits = part.substr(prefix.size());
            if (bits == "32")
                bytes = 4;
            else if (bits == "64")
                bytes = 8;
            else
                throw ParseError(path, line,
                                 "unsupported " + prefix.substr(0, prefix.size() - 1) + " size '" +
                                     bits + "' in arch \"" + arch + "\" (expected 32 or 64)");
            return true;
        };
        if (!parse_size("label=", header.label_bytes))
            parse_size("scalar=", header.scalar_bytes);
        begin = end + 1;
    }
}

std::string arch_string(int label_bytes, int scalar_bytes)
{
    return "LSB;label=" + std::to_string(label_bytes * 8) +
           ";scalar=" + std::to_string(scalar_bytes * 8);
}

FoamHeader parse_header(FoamTokenizer& tokenizer, bool require_format_and_class)
{
    FoamHeader header;
    header.line = read_header_open(tokenizer);
    HeaderEntriesSeen seen;
    while (const std::optional<FoamToken> key = read_header_key(tokenizer, header))
        set_header_entry(tokenizer, *key, read_header_value(tokenizer, *key), header, seen);
    check_required_entries(tokenizer, header, seen, require_format_and_class);
    if (!header.arch.empty())
        parse_arch(header.arch, header, tokenizer.path(), seen.arch_line);
    return header;
}

std::string_view openfoam_banner()
{
    static const std::string text = std::string(banner_top) + banner_body + banner_bottom;
    return text;
}

std::string framed_banner(std::string_view text)
{
    std::string out = banner_top;
    out += "  ";
    out += text;
    out += "\n";
    out += banner_bottom;
    return out;
}

std::string format_header(const FoamHeader& header, std::string_view banner)
{
    std::string out(banner);
    out += "FoamFile\n{\n";
    write_entry(out, "version", header.version.empty() ? "2.0" : header.version);
    write_entry(out, "format", header.is_binary() ? "binary" : "ascii");
    write_entry(out, "class", header.class_name);
    if (header.is_binary())
    {
        const std::string arch = header.arch.empty()
                                     ? arch_string(header.label_bytes, header.scalar_bytes)
                                     : header.arch;
        write_entry(out, "arch", "\"" + arch + "\"");
    }
    if (!header.note.empty())
        write_entry(out, "note", "\"" + header.note + "\"");
    if (!header.location.empty())
        write_entry(out, "location", "\"" + header.location + "\"");
    write_entry(out, "object", header.object);
    out += "}\n";
    out += divider;
    out += "\n";
    return out;
}

std::string format_footer()
{
    return std::string("\n\n") + end_divider;
}

} // namespace meshmorph::io
