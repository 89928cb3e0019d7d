// SPDX-License-Identifier: GPL-3.0-or-later
// Compound lists in dictionaries (List<label>, List<scalar>, ... ascii or binary), read by
// foam_lists' list readers.
#include <utility>

#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_lists.h"

namespace meshmorph::io
{

namespace
{

FoamCompound::Kind compound_kind(std::string_view word, bool& ok)
{
    ok = true;
    if (word == "List<label>")
        return FoamCompound::Kind::label;
    if (word == "List<scalar>")
        return FoamCompound::Kind::scalar;
    if (word == "List<vector>")
        return FoamCompound::Kind::vector;
    if (word == "List<bool>")
        return FoamCompound::Kind::boolean;
    if (word == "List<word>")
        return FoamCompound::Kind::word;
    ok = false;
    return FoamCompound::Kind::label;
}

// The header the list readers need: the format and binary sizes of the dictionary.
FoamHeader list_header(FoamTokenizer& tok, const ParseOptions& options)
{
    if (options.label_bytes != 4 && options.label_bytes != 8)
        throw tok.error("unsupported binary label size " + std::to_string(options.label_bytes));
    if (options.scalar_bytes != 4 && options.scalar_bytes != 8)
        throw tok.error("unsupported binary scalar size " + std::to_string(options.scalar_bytes));
    FoamHeader header;
    header.format = options.binary ? FoamFormat::binary : FoamFormat::ascii;
    header.label_bytes = options.label_bytes;
    header.scalar_bytes = options.scalar_bytes;
    return header;
}

} // namespace

bool is_compound_type(std::string_view word)
{
    bool ok = false;
    compound_kind(word, ok);
    return ok;
}

FoamCompound read_compound(FoamTokenizer& tok, const std::string& type_word,
                           const ParseOptions& options, const std::string& what)
{
    bool ok = false;
    FoamCompound c;
    c.kind = compound_kind(type_word, ok);
    c.type_word = type_word;
    if (!ok)
        throw tok.error("unknown compound list type '" + type_word + "'");
    const FoamHeader header = list_header(tok, options);
    ListReadOptions list_options;
    list_options.what = what.empty() ? type_word : what;
    list_options.max_uniform_size = static_cast<std::size_t>(max_uniform_list_size);
    using Kind = FoamCompound::Kind;
    switch (c.kind)
    {
    case Kind::label:
        c.labels = read_int64_list(tok, header, list_options);
        break;
    case Kind::boolean:
    {
        const std::vector<std::uint8_t> flags = read_bool_list(tok, header, list_options);
        c.labels.assign(flags.begin(), flags.end());
        break;
    }
    case Kind::scalar:
        c.scalars = read_scalar_list(tok, header, list_options);
        break;
    case Kind::vector:
    {
        const Points points = read_vector_list(tok, header, list_options);
        c.scalars.assign(points.data(), points.data() + points.size());
        break;
    }
    case Kind::word:
        c.words = read_word_list(tok, header, list_options);
        break;
    }
    return c;
}

} // namespace meshmorph::io
