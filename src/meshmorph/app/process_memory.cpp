// SPDX-License-Identifier: GPL-3.0-or-later
// Huge pages and heap thresholds for the applications (see the header for why).
#include "meshmorph/app/process_memory.h"

#include "meshmorph/core/sanitizers.h"

#include <cstdlib>
#include <fstream>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#include <unistd.h>
#endif

namespace meshmorph::app
{

namespace
{

std::string environment(const char* name)
{
    const char* value = std::getenv(name);
    return value ? value : "";
}

//! Whether the kernel gives transparent huge pages to regions that ask (madvise or always).
bool kernel_has_huge_pages()
{
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    return std::getline(in, line) && line.find("[never]") == std::string::npos;
}

bool under_valgrind()
{
    return environment("LD_PRELOAD").find("vgpreload") != std::string::npos;
}

#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35))
constexpr bool glibc_has_hugetlb_tunable = true;
#else
constexpr bool glibc_has_hugetlb_tunable = false;
#endif

void restart_with_huge_pages(char** argv)
{
    const std::string tunables = environment("GLIBC_TUNABLES");
    if (!glibc_has_hugetlb_tunable || sanitized || argv == nullptr ||
        environment("MESHMORPH_HUGE_PAGES") != "1" ||
        tunables.find("glibc.malloc.hugetlb") != std::string::npos || under_valgrind() ||
        !kernel_has_huge_pages())
        return;
#if defined(__GLIBC__)
    const std::string with =
        tunables.empty() ? "glibc.malloc.hugetlb=1" : tunables + ":glibc.malloc.hugetlb=1";
    if (setenv("GLIBC_TUNABLES", with.c_str(), 1) != 0)
        return;
    execv("/proc/self/exe", argv);
    // Still here: the re-execution failed. Go on as we are (the tunable is not in effect).
    if (tunables.empty())
        unsetenv("GLIBC_TUNABLES");
    else
        setenv("GLIBC_TUNABLES", tunables.c_str(), 1);
#endif
}

void keep_freed_blocks()
{
#if defined(__GLIBC__)
    if (sanitized)
        return;
    const std::string tunables = environment("GLIBC_TUNABLES");
    if (tunables.find("glibc.malloc.mmap_threshold") == std::string::npos)
        mallopt(M_MMAP_THRESHOLD, 32 << 20); // glibc's largest; larger blocks stay mmap'ed
    if (tunables.find("glibc.malloc.trim_threshold") == std::string::npos)
        mallopt(M_TRIM_THRESHOLD, 1 << 30);
    // One heap for every thread: a block freed by the check that runs alongside the fit
    // (morph/before_check.h) is then reused by the evaluation, where a heap of the check's
    // thread would keep it (100 MB more peak memory on the motorBike). The threads allocate
    // large blocks rarely, so they do not contend for the one heap.
    if (tunables.find("glibc.malloc.arena_max") == std::string::npos)
        mallopt(M_ARENA_MAX, 1);
#endif
}

} // namespace

void configure_process_memory(char** argv)
{
    restart_with_huge_pages(argv);
    keep_freed_blocks();
}

} // namespace meshmorph::app
