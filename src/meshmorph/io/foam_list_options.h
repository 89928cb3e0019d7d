// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The options of one list read (foam_lists.h): a plain record the list readers and
//! their internal parts share.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace meshmorph::io
{

//! Options for one list read.
struct ListReadOptions
{
    //! Name used in messages ("owner", "faces", "internalField").
    std::string what = "list";
    //! When set, the list must have exactly this many elements.
    std::optional<std::size_t> expected_size;
    //! Largest N accepted for a uniform `N{v}` list when no expected_size is given. A
    //! uniform list is a few bytes of text for any N, so N cannot be checked against the
    //! remaining input; this bound keeps a hostile `1000000000000{0}` from allocating.
    std::size_t max_uniform_size = std::size_t(1) << 24;
    //! Parse large ASCII lists with OpenMP threads when the machine has idle cores (1-minute
    //! load average below cores - 1). Results are identical either way.
    bool parallel = true;
    //! Always split ASCII lists into chunks, whatever their size, the load and the number of
    //! threads (for tests of the chunked path).
    bool force_parallel = false;
};

} // namespace meshmorph::io
