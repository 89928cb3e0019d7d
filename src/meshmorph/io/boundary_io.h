// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Reading and writing the bodies of polyMesh `boundary` and `cellZones`/`faceZones`/
//! `pointZones` files (docs/polymesh-format.md §5.4, §5.5). The FoamFile header is read with
//! parse_header() and written with format_header() (foam_header.h).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/io/foam_header.h"
#include "meshmorph/io/foam_tokenizer.h"

namespace meshmorph::io
{

//! \brief Parse a boundary body `N ( name { type …; nFaces …; startFace …; … } … )` from the
//! tokenizer's position (after the header) to the end of the list.
//! `type`, `nFaces` and `startFace` are required; `inGroups` is parsed into in_groups from
//! `1(wall)`, `1 ( wall )`, `(wall)` or `List<word> 1(wall)`; every entry other than
//! type/nFaces/startFace (inGroups included) is kept verbatim in `entries`, in file order.
//! \throw ParseError naming file, line and patch on a missing/invalid entry, a negative
//! nFaces/startFace, or a patch count differing from N.
std::vector<Patch> parse_boundary(FoamTokenizer& tokenizer);

//! \brief Parse a whole boundary file's text (optional FoamFile header, then the body).
std::vector<Patch> parse_boundary(std::string_view text, const std::string& path);

//! \brief Parse a zones body `N ( name { type …Zone; pointLabels|faceLabels|cellLabels
//! List<label> …; flipMap List<bool> …; … } … )`. Lists may be ASCII (`N(…)`, `N{v}`) or
//! binary blocks (when `header.is_binary()`, with the header's label size). `type` is
//! stored in Zone::type; the label list in `labels`; flipMap in `flip_map`; any other entry
//! verbatim in `entries`. A missing label list means an empty zone.
//! \throw ParseError naming file, line and zone on malformed lists, negative labels, a
//! flipMap whose size differs from faceLabels, or a zone count differing from N.
std::vector<Zone> parse_zones(FoamTokenizer& tokenizer, const FoamHeader& header);

//! \brief Parse a whole zones file's text (FoamFile header required, it gives the format).
std::vector<Zone> parse_zones(std::string_view text, const std::string& path);

//! \brief The boundary body as OpenFOAM writes it (`N\n(\n    name\n    {\n        type …`),
//! without trailing newline: a complete file is format_header(h) + body + format_footer().
//! Key order as OpenFOAM: type, physicalType and inGroups (from `entries`, in their order),
//! nFaces, startFace, then the remaining entries verbatim.
std::string format_boundary(const std::vector<Patch>& patches);

//! \brief The zones body as OpenFOAM v1912 writes it (ASCII, or binary label/bool blocks
//! when `format` is binary with `label_bytes` 4 or 8), without trailing newline. The label
//! keyword is chosen from Zone::type (pointLabels/faceLabels/cellLabels).
//! \throw InvalidInput on an unknown zone type or flip_map size mismatch.
std::string format_zones(const std::vector<Zone>& zones, FoamFormat format = FoamFormat::ascii,
                         int label_bytes = 4);

} // namespace meshmorph::io
