// SPDX-License-Identifier: GPL-3.0-or-later
// Memory estimates of the fits (see fit_memory.h).
#include "meshmorph/morph/fit_memory.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/memory_budget.h"

namespace meshmorph::morph
{

double ffd_lattice_bytes(double count)
{
    return 2 * 3 * sizeof(double) * count;
}

std::string format_count(double count)
{
    char text[32];
    std::snprintf(text, sizeof text, count < 1e15 ? "%.0f" : "%.3g", count);
    return text;
}

namespace
{

double lattice_count(const std::array<int, 3>& n)
{
    return double(n[0]) * double(n[1]) * double(n[2]);
}

//! The entry that sets the size of the fit, and what the size is, for the message.
struct SizeSource
{
    const SizeEntry* entry = nullptr;
    std::string what;
};

SizeSource size_source(const DeformationSettings& s, Index n_constraints)
{
    const std::string m = std::to_string(n_constraints) + " constraints";
    switch (s.method)
    {
    case DeformationMethod::dmffd:
        return {&s.dmffd_lattice, "a lattice of " +
                                      format_count(lattice_count(s.dmffd.lattice.control_points)) +
                                      " control points fitted to " + m};
    case DeformationMethod::rbf:
        if (s.greedy || n_constraints > s.direct_limit)
            return {&s.greedy_centres,
                    "a greedy RBF of up to " +
                        std::to_string(s.greedy.value_or(GreedySettings{}).max_centres) +
                        " centres fitted to " + m};
        return {nullptr, "a direct RBF fit of " + m};
    default:
        return {nullptr, "the fit of " + m};
    }
}

} // namespace

double fit_bytes(const DeformationSettings& s, Index n_constraints)
{
    const double m = double(n_constraints);
    const double word = sizeof(double);
    switch (s.method)
    {
    case DeformationMethod::dmffd:
    {
        // Phi (m x n), then the SVD's U (m x r) and Vt (r x n), r = min(m, n).
        const double n = lattice_count(s.dmffd.lattice.control_points);
        return word * (m * n + m * std::min(m, n) + std::min(m, n) * n);
    }
    case DeformationMethod::rbf:
    {
        if (!s.greedy && n_constraints <= s.direct_limit)
            return 2 * word * m * m; // the system and its factor
        const double centres = std::min(m, double(s.greedy.value_or(GreedySettings{}).max_centres));
        return 2 * word * centres * centres; // the centres' system and its factor
    }
    case DeformationMethod::ffd:
        return ffd_lattice_bytes(lattice_count(s.ffd.control_points));
    case DeformationMethod::idw:
        break;
    }
    return 0;
}

void check_fit_memory(const DeformationSettings& s, Index n_constraints)
{
    const std::optional<std::string> shortfall = memory_shortfall(fit_bytes(s, n_constraints));
    if (!shortfall)
        return;
    const SizeSource source = size_source(s, n_constraints);
    const std::string msg = source.what + " " + *shortfall;
    if (source.entry != nullptr && !source.entry->path.empty())
        throw ParseError(source.entry->path, source.entry->line,
                         source.entry->name + ": " + msg + "; make it smaller");
    throw InvalidInput(msg + (source.entry != nullptr
                                  ? " (" + source.entry->name + " sets the size)"
                                  : std::string(" (method idw needs far less)")));
}

} // namespace meshmorph::morph
