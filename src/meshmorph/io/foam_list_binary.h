// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal to the list readers (io/foam_lists.h): decoding the raw bytes of binary list
//! blocks into the build's types. It exists because a binary file's label and scalar sizes
//! follow its header's arch (label 32/64, scalar 32/64), not the build's: labels are
//! converted (and range-checked when narrowed), 4-byte floats widened to double.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "meshmorph/io/foam_list_start.h"
#include "meshmorph/io/foam_tokenizer.h"

namespace meshmorph::io::list_detail
{

//! \brief Decode n labels of `label_bytes` (4 or 8) bytes each from `raw` into `out`.
//! \throw ParseError (binary_error at data_offset + the label's offset) for a 64-bit label
//! that does not fit in a 32-bit `out`.
void decode_labels(std::string_view raw, int label_bytes, std::int32_t* out, std::size_t n,
                   const FoamTokenizer& tok, const ListStart& start, std::size_t data_offset,
                   const std::string& what);
void decode_labels(std::string_view raw, int label_bytes, std::int64_t* out, std::size_t n,
                   const FoamTokenizer& tok, const ListStart& start, std::size_t data_offset,
                   const std::string& what);

//! Decode n scalars of `scalar_bytes` (4 or 8) bytes each from `raw` into `out`.
void decode_scalars(std::string_view raw, int scalar_bytes, double* out, std::size_t n);

} // namespace meshmorph::io::list_detail
