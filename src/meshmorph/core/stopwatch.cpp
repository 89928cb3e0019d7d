// SPDX-License-Identifier: GPL-3.0-or-later
// Seconds formatted for the stage lines of the logs.
#include "meshmorph/core/stopwatch.h"

#include <array>
#include <cstdio>

namespace meshmorph
{

std::string format_seconds(double seconds)
{
    std::array<char, 32> buffer{};
    if (seconds < 0.01)
        std::snprintf(buffer.data(), buffer.size(), "%.3f", seconds);
    else if (seconds >= 100)
        std::snprintf(buffer.data(), buffer.size(), "%.0f", seconds);
    else
        std::snprintf(buffer.data(), buffer.size(), "%.3g", seconds);
    return std::string(buffer.data());
}

} // namespace meshmorph
