// SPDX-License-Identifier: GPL-3.0-or-later
//! \file How much memory this process may still allocate, so that a mesh or dictionary that
//! asks for more fails up front with a message naming it, not in the OOM killer or as a
//! std::bad_alloc deep inside a solver.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace meshmorph
{

//! \brief Bytes this process may still allocate: the kernel's MemAvailable
//! (/proc/meminfo), lowered to what RLIMIT_AS (`ulimit -v`) leaves above the address space
//! in use. nullopt when neither is known (then no up-front check is possible).
std::optional<std::uint64_t> available_memory_bytes();

//! "512 B", "3.2 GB", "24 TB" (powers of 1000, two significant digits at least).
std::string format_bytes(double bytes);

//! \brief When `bytes` exceeds available_memory_bytes(): "needs about X of memory, more
//! than the Y this process may still allocate (MemAvailable, ulimit -v)"; else nullopt.
std::optional<std::string> memory_shortfall(double bytes);

} // namespace meshmorph
