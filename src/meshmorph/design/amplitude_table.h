// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The amplitudes of design variants as a user writes them: one list on the command
//! line (`-variant "(0.1 0 -2)"`) or a design-of-experiments table (`-variants FILE`).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace meshmorph::design
{

//! \brief Parse `(a1 a2 ...)` (or `a1 a2 ...`) of -variant. \throw InvalidInput.
std::vector<double> parse_amplitudes(const std::string& text);

//! \brief A design-of-experiments table: one row of amplitudes per line (numbers separated by
//! blanks or commas); `#` starts a comment; an optional first line of variable names must
//! match the set-up's. \throw IoError; ParseError naming the file and line.
std::vector<std::vector<double>> read_amplitude_table(const std::filesystem::path& path,
                                                      const std::vector<std::string>& names);

} // namespace meshmorph::design
