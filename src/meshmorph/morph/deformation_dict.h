// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Reading the deformation settings from a morphDict: `method` and the `rbf`, `idw`,
//! `dmffd` and `ffd` sub-dictionaries, validated, each error naming its entry.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/morph/deformation_settings.h"

namespace meshmorph::morph
{

//! \brief Read `method` (or `method_override`, the -method option) and the sub-dictionary of
//! the chosen method (absent: defaults). Unknown keywords and bad values are errors.
//! \throw ParseError naming the file, line and keyword; InvalidInput for a bad override.
DeformationSettings read_deformation_settings(const io::FoamDictionary& dict,
                                              const std::optional<std::string>& method_override);

//! `lattice (nx ny nz);` of `d`: at least 4 per axis, a count that fits in memory.
//! \throw ParseError naming the entry.
std::array<int, 3> read_lattice(const io::FoamDictionary& d);

//! The optional `<key> ((x0 y0 z0) (x1 y1 z1));` of `d` as an axis-aligned box.
//! \throw ParseError naming the entry when the corners are not ordered.
std::optional<FfdBox> read_bounds(const io::FoamDictionary& d, const std::string& key = "bounds");

} // namespace meshmorph::morph
