// SPDX-License-Identifier: GPL-3.0-or-later
// Memory checks of the fits (see fit_memory.h); each method's size is its row's
// (deformation_methods.cpp).
#include "meshmorph/morph/fit_memory.h"

#include <cstdio>
#include <optional>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/memory_budget.h"
#include "meshmorph/morph/deformation_methods.h"

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

void check_fit_memory(const DeformationSettings& s, Index n_constraints)
{
    const FitSize size = fit_size(s, n_constraints);
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
