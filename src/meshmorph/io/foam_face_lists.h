// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal to the list readers (io/foam_lists.h): reading one face of a `faceList`,
//! ASCII `k(v0 … vk-1)` / `k{v}` or binary (each face its own label block). It exists
//! because faces are the only list elements of variable size, and because
//! locate_list_element walks face lists element by element as read_face_list does.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/io/foam_header.h"
#include "meshmorph/io/foam_list_start.h"
#include "meshmorph/io/foam_tokenizer.h"

namespace meshmorph::io::list_detail
{

//! \brief Read ASCII face `i` of list `what` (`k(v0 … vk-1)` or `k{v}`), appending its
//! vertex labels to `values`. \throw ParseError naming the face and the line.
void read_ascii_face(FoamTokenizer& tok, std::vector<Index>& values, const ListStart& start,
                     std::size_t i, const std::string& what);

//! \brief Read binary face `i` of list `what` (its own binary label block), appending its
//! vertex labels to `values`.
void read_binary_face(FoamTokenizer& tok, const FoamHeader& header, std::vector<Index>& values,
                      std::size_t i, const std::string& what);

} // namespace meshmorph::io::list_detail
