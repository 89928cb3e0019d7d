// SPDX-License-Identifier: GPL-3.0-or-later
// The list readers of io/foam_lists.h for elements of one fixed size (labels, scalars, bools,
// words, vectors). The pieces they share are in their own files:
// io/foam_list_start.h (size and brackets), io/foam_list_kernels.h (fast ASCII kernels, run
// here so that they inline), io/foam_list_binary.h (binary blocks); faces are in
// io/foam_face_lists.cpp and the writers in io/foam_list_writers.cpp.
#include "meshmorph/io/foam_lists.h"

#include <cstdint>
#include <exception>
#include <limits>
#include <type_traits>

#include "meshmorph/io/foam_list_binary.h"
#include "meshmorph/io/foam_list_kernels.h"
#include "meshmorph/io/foam_list_start.h"

namespace meshmorph::io
{

using namespace list_detail; // the list readers' shared parts (internal headers above)

namespace
{

// ---------------------------------------------------------------------------------------
// ASCII elements read with the tokenizer (precise errors).

template <class L>
void read_ascii_label(FoamTokenizer& tok, L& out, const ListStart& start, std::size_t i,
                      const std::string& what)
{
    std::int64_t v;
    if (!tok.read_label(v))
        throw_short_list(tok, start, i, what, "an integer");
    out = to_label<L>(v, tok, what);
}

inline void read_ascii_scalar(FoamTokenizer& tok, double& out, const ListStart& start,
                              std::size_t i, const std::string& what)
{
    if (!tok.read_scalar(out))
        throw_short_list(tok, start, i, what, "a number");
}

inline void read_ascii_vector(FoamTokenizer& tok, double* out, const ListStart& start,
                              std::size_t i, const std::string& what)
{
    tok.skip_whitespace_and_comments();
    if (tok.offset() >= tok.buffer().size() || tok.buffer()[tok.offset()] != '(')
        throw_short_list(tok, start, i, what, "a vector '(x y z)'");
    tok.read_vector(out);
}

// Reads a list with one value of type T per element (labels, scalars, bools, words):
// `element_bytes` is its size in a binary block, 0 for a type that is not contiguous (its
// lists stay ASCII tokens in binary files). `read_ascii(tok, T&, start, i, what)` reads one
// element with the tokenizer (precise errors); `decode(raw, T*, n, tok, start, data_offset,
// what)` converts n elements of a binary block; `fast_one(p, e, T&)` is the kernel for big
// ASCII bodies, or nullptr for element types that have none.
template <class T, class ReadAscii, class Decode, class Fast>
std::vector<T> read_flat_list(FoamTokenizer& tok, const FoamHeader& header,
                              const ListReadOptions& options, std::size_t element_bytes,
                              const char* kind, ReadAscii read_ascii, Decode decode, Fast fast_one)
{
    const bool binary = header.is_binary() && element_bytes > 0;
    const ListStart start =
        read_list_start(tok, header, options, min_chars_label, binary ? element_bytes : 0);
    std::vector<T> values;
    if (start.open == 0)
        return values;
    if (binary)
    {
        const std::size_t n = start.open == '{' ? 1 : start.size;
        const std::size_t data_offset = tok.offset();
        if (n * element_bytes > remaining(tok))
            throw binary_error(tok, start.line, data_offset, options.what,
                               "truncated: " + size_text(n * element_bytes) +
                                   " bytes of data expected, " + size_text(remaining(tok)) +
                                   " remain");
        const std::string_view raw = tok.read_raw(n * element_bytes);
        values.resize(n);
        decode(raw, values.data(), n, tok, start, data_offset, options.what);
        expect_binary_close(tok, start, options.what, data_offset, start.open == '{' ? '}' : ')');
        if (start.open == '{')
            values.assign(start.size, values.empty() ? T{} : values[0]);
        return values;
    }
    if (start.open == '{')
    {
        T v{};
        read_ascii(tok, v, start, 0, options.what);
        expect_close(tok, start, options.what, kind);
        values.assign(start.size, v);
        return values;
    }
    if (start.has_size)
    {
        values.resize(start.size);
        if constexpr (!std::is_same_v<Fast, std::nullptr_t>)
        {
            T* const out = values.data();
            const std::string_view buf = tok.buffer();
            if (parse_fast(
                    tok, start, options, 0,
                    [out, fast_one](const char*& p, const char* e, std::size_t i)
                    { return fast_one(p, e, out[i]); },
                    [&buf](const Chunk& c) { return count_tokens(buf, c); }, kind))
                return values;
        }
        for (std::size_t i = 0; i < start.size; ++i)
            read_ascii(tok, values[i], start, i, options.what);
        expect_close(tok, start, options.what, kind);
        return values;
    }
    // Unsized `( … )`.
    for (;;)
    {
        tok.skip_whitespace_and_comments();
        if (tok.offset() < tok.buffer().size() && tok.buffer()[tok.offset()] == ')')
            break;
        T v{};
        read_ascii(tok, v, start, values.size(), options.what);
        values.push_back(std::move(v));
    }
    tok.expect(')');
    if (options.expected_size && values.size() != *options.expected_size)
        throw tok.error_at(start.line, "list '" + options.what + "' has " +
                                           size_text(values.size()) + " elements, expected " +
                                           size_text(*options.expected_size));
    return values;
}

template <class L>
std::vector<L> read_labels_as(FoamTokenizer& tok, const FoamHeader& header,
                              const ListReadOptions& options)
{
    const int bytes = header.label_bytes;
    return read_flat_list<L>(
        tok, header, options, static_cast<std::size_t>(bytes), "label", read_ascii_label<L>,
        [bytes](std::string_view raw, L* out, std::size_t n, const FoamTokenizer& t,
                const ListStart& start, std::size_t offset, const std::string& what)
        { decode_labels(raw, bytes, out, n, t, start, offset, what); },
        [](const char*& p, const char* e, L& out) { return fast::label(p, e, out); });
}

// A bool element: OpenFOAM writes 0/1 (also true/false, on/off, yes/no in hand-written
// files); any other number or word is an error.
void read_ascii_bool(FoamTokenizer& tok, std::uint8_t& out, const ListStart& start, std::size_t i,
                     const std::string& what)
{
    std::int64_t v = 0;
    if (tok.read_label(v))
    {
        if (v != 0 && v != 1)
            throw tok.error("element " + size_text(i) + " of list '" + what + "' is " +
                            std::to_string(v) + ", not a bool (0 or 1)");
        out = static_cast<std::uint8_t>(v);
        return;
    }
    const FoamToken& t = tok.peek();
    if (t.is_word("true") || t.is_word("on") || t.is_word("yes"))
        out = 1;
    else if (t.is_word("false") || t.is_word("off") || t.is_word("no"))
        out = 0;
    else
        throw_short_list(tok, start, i, what, "a bool (0/1, true/false, on/off, yes/no)");
    tok.next();
}

// A word element: a word or a quoted string.
void read_ascii_word(FoamTokenizer& tok, std::string& out, const ListStart& start, std::size_t i,
                     const std::string& what)
{
    const FoamToken& t = tok.peek();
    if (!t.is_word() && !t.is_string())
        throw_short_list(tok, start, i, what, "a word");
    out = tok.next().text;
}

} // namespace

void expect_end_of_file(FoamTokenizer& tok, const std::string& what)
{
    if (!tok.at_end())
    {
        const FoamToken& t = tok.peek();
        throw tok.error_at(t.line, "unexpected " + t.describe() + " after the " + what +
                                       " list (expected end of file)");
    }
}

std::vector<Index> read_label_list(FoamTokenizer& tok, const FoamHeader& header,
                                   const ListReadOptions& options)
{
    return read_labels_as<Index>(tok, header, options);
}

std::vector<double> read_scalar_list(FoamTokenizer& tok, const FoamHeader& header,
                                     const ListReadOptions& options)
{
    const int bytes = header.scalar_bytes;
    return read_flat_list<double>(
        tok, header, options, static_cast<std::size_t>(bytes), "scalar", read_ascii_scalar,
        [bytes](std::string_view raw, double* out, std::size_t n, const FoamTokenizer&,
                const ListStart&, std::size_t, const std::string&)
        { decode_scalars(raw, bytes, out, n); },
        [](const char*& p, const char* e, double& out) { return fast::scalar(p, e, out); });
}

std::vector<std::int64_t> read_int64_list(FoamTokenizer& tok, const FoamHeader& header,
                                          const ListReadOptions& options)
{
    return read_labels_as<std::int64_t>(tok, header, options);
}

std::vector<std::uint8_t> read_bool_list(FoamTokenizer& tok, const FoamHeader& header,
                                         const ListReadOptions& options)
{
    return read_flat_list<std::uint8_t>(
        tok, header, options, 1, "bool", read_ascii_bool,
        [](std::string_view raw, std::uint8_t* out, std::size_t n, const FoamTokenizer&,
           const ListStart&, std::size_t, const std::string&)
        {
            for (std::size_t i = 0; i < n; ++i)
                out[i] = raw[i] != 0 ? 1 : 0;
        },
        nullptr);
}

std::vector<std::string> read_word_list(FoamTokenizer& tok, const FoamHeader& header,
                                        const ListReadOptions& options)
{
    return read_flat_list<std::string>(
        tok, header, options, 0, "word", read_ascii_word,
        [](std::string_view, std::string*, std::size_t, const FoamTokenizer&, const ListStart&,
           std::size_t, const std::string&) {},
        nullptr);
}

Points read_vector_list(FoamTokenizer& tok, const FoamHeader& header,
                        const ListReadOptions& options)
{
    const std::size_t vector_bytes = 3 * static_cast<std::size_t>(header.scalar_bytes);
    const ListStart start = read_list_start(tok, header, options, min_chars_vector,
                                            header.is_binary() ? vector_bytes : 0);
    Points points;
    if (start.open == 0)
        return points;
    if (header.is_binary())
    {
        const std::size_t n = start.open == '{' ? 1 : start.size;
        const std::size_t data_offset = tok.offset();
        if (n > remaining(tok) / vector_bytes)
            throw binary_error(tok, start.line, data_offset, options.what, "truncated data");
        const std::string_view raw = tok.read_raw(n * vector_bytes);
        points.resize(static_cast<Eigen::Index>(n), 3);
        decode_scalars(raw, header.scalar_bytes, points.data(), 3 * n);
        expect_binary_close(tok, start, options.what, data_offset, start.open == '{' ? '}' : ')');
        if (start.open == '{')
        {
            const Eigen::RowVector3d v = points.row(0);
            points.resize(static_cast<Eigen::Index>(start.size), 3);
            points.rowwise() = v;
        }
        return points;
    }
    if (start.open == '{')
    {
        double v[3];
        read_ascii_vector(tok, v, start, 0, options.what);
        expect_close(tok, start, options.what, "vector");
        points.resize(static_cast<Eigen::Index>(start.size), 3);
        points.rowwise() = Eigen::RowVector3d(v[0], v[1], v[2]);
        return points;
    }
    if (start.has_size)
    {
        points.resize(static_cast<Eigen::Index>(start.size), 3);
        double* const data = points.data();
        const std::string_view buf = tok.buffer();
        if (parse_fast(
                tok, start, options, 1,
                [data](const char*& p, const char* e, std::size_t i)
                { return fast::vector(p, e, data + 3 * i); },
                [&buf](const Chunk& c) { return count_char(buf, c, '('); }, "vector"))
            return points;
        for (std::size_t i = 0; i < start.size; ++i)
            read_ascii_vector(tok, data + 3 * i, start, i, options.what);
        expect_close(tok, start, options.what, "vector");
        return points;
    }
    std::vector<double> flat;
    for (;;)
    {
        tok.skip_whitespace_and_comments();
        if (tok.offset() < tok.buffer().size() && tok.buffer()[tok.offset()] == ')')
            break;
        double v[3];
        read_ascii_vector(tok, v, start, flat.size() / 3, options.what);
        flat.insert(flat.end(), v, v + 3);
    }
    tok.expect(')');
    const std::size_t n = flat.size() / 3;
    if (options.expected_size && n != *options.expected_size)
        throw tok.error_at(start.line, "list '" + options.what + "' has " + size_text(n) +
                                           " elements, expected " +
                                           size_text(*options.expected_size));
    points = Eigen::Map<const Points>(flat.data(), static_cast<Eigen::Index>(n), 3);
    return points;
}

} // namespace meshmorph::io
