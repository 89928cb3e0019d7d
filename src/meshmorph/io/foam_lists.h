// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Readers and writers of OpenFOAM's list syntax, ASCII or binary
//! (docs/polymesh-format.md §4, §5.2): the big lists of polyMesh files (labels, scalars,
//! vectors, faces) and the `List<T>` compounds of dictionaries (also bools and words), so
//! that each rule of the syntax (sizes, uniform lists, the bare `0` of an empty binary list,
//! truncation checks) is written once.
//!
//! Readers start at the tokenizer's position (after the FoamFile header, or after a
//! `List<T>` word) and consume exactly one list. ASCII forms: `N(…)` on one or many lines,
//! `N{v}`, unsized `(…)`, `0()`. Binary forms: `N` `(` raw bytes `)`, and `0` alone.
//! Binary sizes follow the header's arch (label 32/64, scalar 32/64; converted to Index
//! and double). Every declared count is checked against the bytes left in the buffer
//! before anything is allocated, so hostile input cannot cause huge allocations.
//!
//! Errors are ParseError: ASCII ones carry the file and line; binary ones the line where
//! the block starts plus "byte offset B" inside the file.
//!
//! Implemented in foam_lists.cpp (lists of one-size elements), foam_face_lists.cpp (faces)
//! and foam_list_writers.cpp (append_*), over internal parts: foam_list_start.h (sizes and
//! brackets), foam_list_kernels.h (fast ASCII kernels), foam_list_binary.h (binary blocks).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/types.h"
#include "meshmorph/io/foam_header.h"
#include "meshmorph/io/foam_list_options.h"
#include "meshmorph/io/foam_tokenizer.h"

namespace meshmorph::io
{

//! \brief Read a label list (ASCII or, if `header.is_binary()`, binary with
//! header.label_bytes). Values must fit in Index.
//! \throw ParseError on malformed input, size mismatch, truncated data, labels out of range.
std::vector<Index> read_label_list(FoamTokenizer& tokenizer, const FoamHeader& header,
                                   const ListReadOptions& options = {});

//! \brief Read a scalar list (binary: header.scalar_bytes, 4-byte floats are converted).
std::vector<double> read_scalar_list(FoamTokenizer& tokenizer, const FoamHeader& header,
                                     const ListReadOptions& options = {});

//! \brief Read a label list as 64-bit integers whatever the build's Index (dictionary
//! values such as `List<label>` compounds); otherwise as read_label_list.
std::vector<std::int64_t> read_int64_list(FoamTokenizer& tokenizer, const FoamHeader& header,
                                          const ListReadOptions& options = {});

//! \brief Read a bool list as 0/1 bytes: binary one byte per element (non-zero is true);
//! ASCII `0`/`1`, also `true`/`false`, `on`/`off`, `yes`/`no`.
//! \throw ParseError on another number or word, as for the other lists.
std::vector<std::uint8_t> read_bool_list(FoamTokenizer& tokenizer, const FoamHeader& header,
                                         const ListReadOptions& options = {});

//! \brief Read a word list (words or quoted strings). Words are not contiguous, so the list
//! is ASCII tokens even in a binary file.
std::vector<std::string> read_word_list(FoamTokenizer& tokenizer, const FoamHeader& header,
                                        const ListReadOptions& options = {});

//! \brief Read a vector list as n x 3 points (ASCII `(x y z)` elements; binary 3 scalars).
Points read_vector_list(FoamTokenizer& tokenizer, const FoamHeader& header,
                        const ListReadOptions& options = {});

//! \brief Read a face list: `faceList` (ASCII `N ( k(v…) … )`, or binary with each face its
//! own binary block) or `faceCompactList` (two label lists: nFaces+1 offsets starting at 0
//! and non-decreasing, then offsets[nFaces] vertex labels), ASCII or binary, chosen by
//! `compact`. Vertex labels are not range-checked here (the caller knows nPoints).
//! \throw ParseError on malformed input, bad offsets or truncated data.
CompactList read_face_list(FoamTokenizer& tokenizer, const FoamHeader& header, bool compact,
                           const ListReadOptions& options = {});

//! Element kinds for locate_list_element.
enum class ListKind
{
    label,
    scalar,
    vector,
    face,               //!< faceList element (face index)
    face_compact_value, //!< faceCompactList: index into the flat vertex-label list
};

//! Where a list element is in its file, for messages about values found invalid after
//! parsing.
struct ElementLocation
{
    std::size_t line = 0;        //!< line of the element (ASCII) or of the block start (binary)
    std::size_t byte_offset = 0; //!< byte offset of the element in the file
};

//! \brief Locate element `index` of the list starting at the tokenizer's position (reads
//! serially up to it; meant for error paths only). Returns {0, 0} if the list cannot be
//! walked that far.
ElementLocation locate_list_element(FoamTokenizer& tokenizer, const FoamHeader& header,
                                    ListKind kind, std::size_t index);

//! \brief Check that only whitespace and comments follow a list body.
//! \throw ParseError "unexpected ... after the list" naming file and line.
void expect_end_of_file(FoamTokenizer& tokenizer, const std::string& what);

//! \brief Append a label list body: binary `\nN\n(` raw `)` (`0` alone when empty) or, ASCII,
//! OpenFOAM's layout (`N(a b)` for N <= 10 on one line, else `N\n(\na\nb\n)`; `N{v}` for
//! uniform lists with N >= 2 when `allow_uniform`). No leading/trailing newline for ASCII.
void append_label_list(std::string& out, const std::vector<Index>& values, FoamFormat format,
                       int label_bytes = 4, bool allow_uniform = true);

//! \brief Append a vector list body: ASCII `N\n(\n(x y z)\n…)` with `digits` significant
//! digits (one line `N((x y z) …)` for N <= 10, like OpenFOAM), or binary raw doubles.
void append_vector_list(std::string& out, const Points& values, FoamFormat format, int digits = 17);

//! \brief Append a face list: ASCII `faceList` (`N\n(\nk(v…)\n…)`), or binary
//! `faceCompactList` (offsets block then flat block).
void append_face_list(std::string& out, const CompactList& faces, FoamFormat format,
                      int label_bytes = 4);

} // namespace meshmorph::io
