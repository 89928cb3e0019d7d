// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal to the list readers (io/foam_lists.h): how an OpenFOAM list starts (`N(`,
//! `N{`, `(`, a bare `0`) and ends, with the checks that keep hostile sizes from allocating
//! and the messages every list reader shares. It exists so that the readers of each element
//! kind (flat lists, vectors, faces) and the fast kernels agree on these rules.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "meshmorph/core/types.h"
#include "meshmorph/io/foam_header.h"
#include "meshmorph/io/foam_list_options.h"
#include "meshmorph/io/foam_tokenizer.h"

namespace meshmorph::io::list_detail
{

// Smallest number of characters an ASCII element can take (with its separator), used to
// reject declared sizes the remaining text cannot possibly hold.
constexpr std::size_t min_chars_label = 2;  // "0 "
constexpr std::size_t min_chars_vector = 7; // "(0 0 0)"
constexpr std::size_t min_chars_face = 8;   // "3(0 1 2)"

inline std::string size_text(std::size_t n)
{
    return std::to_string(n);
}

inline std::size_t remaining(const FoamTokenizer& tok)
{
    return tok.buffer().size() - tok.offset();
}

//! "path:line: binary list 'what' at byte offset B: msg".
ParseError binary_error(const FoamTokenizer& tok, std::size_t line, std::size_t byte_offset,
                        const std::string& what, const std::string& msg);

//! A label read as int64 converted to the list's label type L (Index, or int64 for
//! dictionary values), range-checked when L is narrower.
template <class L = Index>
L to_label(std::int64_t v, const FoamTokenizer& tok, const std::string& what)
{
    if constexpr (sizeof(L) < sizeof(std::int64_t))
    {
        if (v < std::numeric_limits<L>::min() || v > std::numeric_limits<L>::max())
            throw tok.error("label " + std::to_string(v) + " in '" + what + "' does not fit in a " +
                            std::to_string(8 * sizeof(L)) + "-bit label");
    }
    return static_cast<L>(v);
}

//! What starts a list: its declared size (or none for `( … )`), and the bracket.
struct ListStart
{
    bool has_size = false;
    std::size_t size = 0;
    char open = '('; // '(' , '{' (uniform), or 0 for an empty binary list without brackets
    std::size_t line = 0;
};

//! \brief Reads `N` and the opening bracket (ASCII or binary), validating N against the
//! bytes left: at least `ascii_min_chars` per ASCII element, exactly `binary_element_bytes`
//! per binary one (0: the list is ASCII even in a binary file).
ListStart read_list_start(FoamTokenizer& tok, const FoamHeader& header,
                          const ListReadOptions& options, std::size_t ascii_min_chars,
                          std::size_t binary_element_bytes);

//! After a binary block: the closing bracket must follow immediately.
void expect_binary_close(FoamTokenizer& tok, const ListStart& start, const std::string& what,
                         std::size_t data_offset, char close = ')');

//! An ASCII list ended, or held something else, where element `got` of `kind` was expected.
[[noreturn]] void throw_short_list(FoamTokenizer& tok, const ListStart& start, std::size_t got,
                                   const std::string& what, const char* kind);

//! The closing bracket of an ASCII list of `kind`s after its last element.
void expect_close(FoamTokenizer& tok, const ListStart& start, const std::string& what,
                  const char* kind);

} // namespace meshmorph::io::list_detail
