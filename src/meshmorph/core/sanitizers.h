// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Whether this build runs under a sanitizer (GCC's and Clang's ways of saying so).
#pragma once

#if defined(__has_feature)
#define MESHMORPH_HAS_FEATURE(x) __has_feature(x)
#else
#define MESHMORPH_HAS_FEATURE(x) 0
#endif

namespace meshmorph
{

#if defined(__SANITIZE_ADDRESS__) || MESHMORPH_HAS_FEATURE(address_sanitizer)
inline constexpr bool address_sanitized = true;
#else
inline constexpr bool address_sanitized = false;
#endif

//! Any sanitizer that replaces malloc (address, thread, memory).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__) ||                               \
    MESHMORPH_HAS_FEATURE(address_sanitizer) || MESHMORPH_HAS_FEATURE(thread_sanitizer) ||         \
    MESHMORPH_HAS_FEATURE(memory_sanitizer)
inline constexpr bool sanitized = true;
#else
inline constexpr bool sanitized = false;
#endif

} // namespace meshmorph
