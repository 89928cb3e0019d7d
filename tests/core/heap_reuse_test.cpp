// SPDX-License-Identifier: GPL-3.0-or-later
// keep_freed_blocks_in_heap: an array of a mesh's size freed and allocated again is served
// from memory already touched, without the kernel's page faults of fresh pages.
#include "meshmorph/core/heap_reuse.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <memory>

#include <sys/resource.h>

namespace meshmorph
{
namespace
{

#if defined(__SANITIZE_ADDRESS__)
constexpr bool sanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool sanitized = true;
#else
constexpr bool sanitized = false;
#endif
#else
constexpr bool sanitized = false;
#endif

long minor_faults()
{
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_minflt;
}

//! The page faults of allocating and filling `bytes` once more after the same was freed.
long faults_of_a_second_array(std::size_t bytes)
{
    const auto fill = [bytes]
    {
        std::unique_ptr<char[]> block(new char[bytes]);
        std::memset(block.get(), 1, bytes);
        return block[bytes - 1]; // keeps the fill
    };
    (void)fill();
    const long before = minor_faults();
    (void)fill();
    return minor_faults() - before;
}

TEST(HeapReuse, a_freed_array_of_24_mb_is_reused_without_faulting_its_pages_in_again)
{
    if (sanitized)
        GTEST_SKIP() << "the sanitizer's allocator ignores malloc's thresholds";
    if (std::getenv("MALLOC_MMAP_THRESHOLD_") != nullptr || std::getenv("GLIBC_TUNABLES"))
        GTEST_SKIP() << "a malloc threshold set in the environment is left alone";
    keep_freed_blocks_in_heap();
    // 24 MB, a million faces' vectors: 6144 pages of 4 kB if mapped afresh.
    const std::size_t bytes = std::size_t(24) << 20;
    EXPECT_LT(faults_of_a_second_array(bytes), 100);
}

} // namespace
} // namespace meshmorph
