// SPDX-License-Identifier: GPL-3.0-or-later
// Available memory from /proc/meminfo and RLIMIT_AS (Linux; elsewhere: unknown).
#include "meshmorph/core/memory_budget.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace meshmorph
{

namespace
{

//! The value of `key` in a /proc file of "key:  value kB" lines, in bytes.
std::optional<std::uint64_t> proc_kb_value(const char* file, const std::string& key)
{
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line))
        if (line.compare(0, key.size(), key) == 0 && line.size() > key.size() &&
            line[key.size()] == ':')
        {
            std::istringstream s(line.substr(key.size() + 1));
            std::uint64_t kb = 0;
            if (s >> kb)
                return kb * 1024;
        }
    return std::nullopt;
}

} // namespace

std::optional<std::uint64_t> available_memory_bytes()
{
    std::optional<std::uint64_t> available = proc_kb_value("/proc/meminfo", "MemAvailable");
    rlimit limit{};
    if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    {
        const std::uint64_t used = proc_kb_value("/proc/self/status", "VmSize").value_or(0);
        const std::uint64_t cap = limit.rlim_cur > used ? limit.rlim_cur - used : 0;
        available = available ? std::min(*available, cap) : cap;
    }
    return available;
}

std::string format_bytes(double bytes)
{
    static const char* const units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
    int u = 0;
    while (bytes >= 1000 && u < 6)
    {
        bytes /= 1000;
        ++u;
    }
    char text[32];
    std::snprintf(text, sizeof text, bytes < 10 && u > 0 ? "%.1f %s" : "%.0f %s", bytes, units[u]);
    return text;
}

std::optional<std::string> memory_shortfall(double bytes)
{
    const std::optional<std::uint64_t> available = available_memory_bytes();
    if (!available || bytes <= static_cast<double>(*available))
        return std::nullopt;
    return "needs about " + format_bytes(bytes) + " of memory, more than the " +
           format_bytes(static_cast<double>(*available)) +
           " this process may still allocate (MemAvailable, ulimit -v)";
}

} // namespace meshmorph
