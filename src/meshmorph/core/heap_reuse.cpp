// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/core/heap_reuse.h"

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace meshmorph
{

namespace
{

bool user_set_threshold()
{
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    return std::getenv("MALLOC_MMAP_THRESHOLD_") != nullptr ||
           (tunables != nullptr && std::strstr(tunables, "mmap_threshold") != nullptr);
}

} // namespace

void keep_freed_blocks_in_heap()
{
#if defined(__GLIBC__)
    constexpr int largest_heap_block = 32 * 1024 * 1024; // glibc refuses more (64-bit)
    // Fixing the threshold also fixes glibc's trim threshold at 128 kB, so that a block
    // freed at the top of the heap would go back to the kernel at once: keep up to 256 MB.
    constexpr int kept_at_top = 256 * 1024 * 1024;
    if (user_set_threshold())
        return;
    mallopt(M_MMAP_THRESHOLD, largest_heap_block);
    mallopt(M_TRIM_THRESHOLD, kept_at_top);
#endif
}

} // namespace meshmorph
