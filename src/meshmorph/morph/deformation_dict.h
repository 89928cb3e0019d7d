// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Reading the deformation settings from a morphDict: `method` and the `rbf`, `idw`,
//! `dmffd` and `ffd` sub-dictionaries, validated, each error naming its entry.
#pragma once

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

} // namespace meshmorph::morph
