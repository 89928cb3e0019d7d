// SPDX-License-Identifier: GPL-3.0-or-later
// Memory checks of the fits (see fit_memory.h); each method's size comes from its row
// (deformation_methods.cpp: fit_size).
#include "meshmorph/morph/fit_memory.h"

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

void check_fit_memory(const FitSize& size)
{
    const std::optional<std::string> shortfall = memory_shortfall(size.bytes);
    if (!shortfall)
        return;
    const std::string msg = size.what + " " + *shortfall;
    if (size.entry != nullptr && !size.entry->path.empty())
        throw ParseError(size.entry->path, size.entry->line,
                         size.entry->name + ": " + msg + "; make it smaller");
    throw InvalidInput(msg + (size.entry != nullptr ? " (" + size.entry->name + " sets the size)"
                                                    : std::string(" (method idw needs far less)")));
}

} // namespace meshmorph::morph
