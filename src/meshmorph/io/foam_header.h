// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The `FoamFile { ... }` header of OpenFOAM data files (docs/polymesh-format.md §3):
//! parsing, and writing it exactly as OpenFOAM v1912 does (banner, header, divider).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "meshmorph/io/foam_tokenizer.h"

namespace meshmorph::io
{

enum class FoamFormat
{
    ascii,
    binary
};

//! Contents of a `FoamFile` header.
struct FoamHeader
{
    std::string version = "2.0";
    FoamFormat format = FoamFormat::ascii;
    std::string class_name; //!< `class`, e.g. vectorField, faceList, polyBoundaryMesh
    std::string object;     //!< `object`, e.g. points
    std::string location;   //!< `location` without quotes; empty when absent
    std::string note;       //!< `note` without quotes; empty when absent
    std::string arch;       //!< `arch` as written, e.g. "LSB;label=32;scalar=64"; empty when absent
    int label_bytes = 4;    //!< from arch `label=32|64` (4 or 8); 4 when absent
    int scalar_bytes = 8;   //!< from arch `scalar=32|64` (4 or 8); 8 when absent
    std::size_t line = 0;   //!< line of the `FoamFile` keyword (0 when built in code)

    bool is_binary() const { return format == FoamFormat::binary; }
};

//! \brief Read the optional banner comments and the `FoamFile { ... }` block, leaving the
//! tokenizer just after its closing `}`. Unknown header keys are ignored.
//! \param require_format_and_class false for dictionaries (format defaults to ascii,
//! class may be absent); data files keep the default true.
//! \throw ParseError naming path and line when `FoamFile` is missing, when `format` or
//! `class` is missing (if required), when `format` is neither ascii nor binary, or when
//! `arch` says `MSB` or has a label/scalar size other than 32/64.
FoamHeader parse_header(FoamTokenizer& tokenizer, bool require_format_and_class = true);

//! \brief Whether the next token of `tokenizer` is the word `FoamFile` (nothing consumed).
bool has_header(FoamTokenizer& tokenizer);

//! \brief Parse an arch string "LSB;label=32;scalar=64" into `header.label_bytes` /
//! `header.scalar_bytes`. Missing parts keep the defaults (4 and 8).
//! \throw ParseError (with `path`, `line`) on `MSB` or sizes other than 32/64.
void parse_arch(const std::string& arch, FoamHeader& header, const std::string& path,
                std::size_t line);

//! The arch string OpenFOAM writes: "LSB;label=<32|64>;scalar=<32|64>".
std::string arch_string(int label_bytes, int scalar_bytes);

//! The banner OpenFOAM v1912 (Debian build) writes at the top of its files, byte for byte
//! (7 lines, each ending in '\n').
std::string_view openfoam_banner();

//! \brief A 3-line banner for files meshmorph writes on its own account: the first and last
//! lines of openfoam_banner() around the line "  <text>\n" (two spaces, then `text`, e.g.
//! "Written by meshMorph 1.0 (checkMeshQuality)").
std::string framed_banner(std::string_view text);

//! \brief The one writer of `FoamFile` headers: `banner` + `FoamFile` block + divider, byte
//! for byte as OpenFOAM v1912 (Debian build) writes them, ending with "// * * ... * //\n\n".
//! Keys in OpenFOAM's order: version ("2.0" when empty), format, class, arch (binary only;
//! built from label_bytes/scalar_bytes when `arch` is empty), note (quoted; omitted when
//! empty), location (quoted; omitted when empty), object.
//! A complete file is `format_header(h) + body + format_footer()`.
//! \param banner written first as is: OpenFOAM's by default, or framed_banner(...).
std::string format_header(const FoamHeader& header, std::string_view banner = openfoam_banner());

//! The closing divider OpenFOAM writes after a body: "\n\n// ***...*** //\n".
std::string format_footer();

} // namespace meshmorph::io
