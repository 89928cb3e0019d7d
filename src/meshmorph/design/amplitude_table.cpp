// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/design/amplitude_table.h"

#include <cmath>
#include <sstream>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_file.h"

namespace meshmorph::design
{

namespace
{

//! The words of a line: separated by blanks and commas, `#` to the end ignored.
std::vector<std::string> words_of(std::string line)
{
    line = line.substr(0, line.find('#'));
    for (char& c : line)
        if (c == ',' || c == '(' || c == ')' || c == '\t' || c == '\r')
            c = ' ';
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string w; in >> w;)
        words.push_back(w);
    return words;
}

//! A finite number, or nullopt.
std::optional<double> number(const std::string& w)
{
    std::size_t used = 0;
    try
    {
        const double v = std::stod(w, &used);
        if (used == w.size() && std::isfinite(v))
            return v;
    }
    catch (const std::exception&)
    {
    }
    return std::nullopt;
}

//! Which column of a header differs from the set-up's variables, and what was expected.
std::string header_mismatch(const std::vector<std::string>& header,
                            const std::vector<std::string>& names)
{
    std::string expected;
    for (const std::string& n : names)
        expected += (expected.empty() ? "" : " ") + n;
    std::size_t k = 0;
    while (k < header.size() && k < names.size() && header[k] == names[k])
        ++k;
    std::string what;
    if (k < header.size() && k < names.size())
        what = "column " + std::to_string(k + 1) + " is '" + header[k] + "' where the set-up's " +
               "variable " + std::to_string(k + 1) + " is '" + names[k] + "'";
    else if (k < names.size())
        what = "the header ends at column " + std::to_string(k) + ", before variable '" + names[k] +
               "'";
    else
        what = "column " + std::to_string(k + 1) + " ('" + header[k] +
               "') is beyond the set-up's " + std::to_string(names.size()) + " variables";
    return "the header's variable names differ from the set-up's: " + what +
           " (expected, in the morphDict's order: " + expected + ")";
}

} // namespace

std::vector<double> parse_amplitudes(const std::string& text)
{
    std::vector<double> a;
    for (const std::string& w : words_of(text))
    {
        const std::optional<double> v = number(w);
        if (!v)
            throw InvalidInput("-variant: '" + w +
                               "' is not a finite number (expected a list "
                               "of amplitudes, e.g. \"(0.1 0 -2)\")");
        a.push_back(*v);
    }
    if (a.empty())
        throw InvalidInput("-variant: no amplitudes (expected e.g. \"(0.1 0 -2)\")");
    return a;
}

std::vector<std::vector<double>> read_amplitude_table(const std::filesystem::path& path,
                                                      const std::vector<std::string>& names)
{
    std::istringstream in(io::read_foam_file(path).data);
    std::vector<std::vector<double>> rows;
    std::size_t line_no = 0;
    for (std::string line; std::getline(in, line);)
    {
        ++line_no;
        const std::vector<std::string> words = words_of(line);
        if (words.empty())
            continue;
        if (rows.empty() && !number(words.front()))
        {
            if (words != names)
                throw ParseError(path.string(), line_no, header_mismatch(words, names));
            continue;
        }
        std::vector<double> row;
        for (const std::string& w : words)
        {
            const std::optional<double> v = number(w);
            if (!v)
                throw ParseError(path.string(), line_no, "'" + w + "' is not a finite number");
            row.push_back(*v);
        }
        if (row.size() != names.size())
            throw ParseError(path.string(), line_no,
                             std::to_string(row.size()) + " amplitudes, expected " +
                                 std::to_string(names.size()) + " (one per design variable)");
        rows.push_back(std::move(row));
    }
    if (rows.empty())
        throw ParseError(path.string(), line_no, "no rows of amplitudes");
    return rows;
}

} // namespace meshmorph::design
