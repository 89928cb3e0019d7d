// SPDX-License-Identifier: GPL-3.0-or-later
// Face lists (read_face_list in io/foam_lists.h): `faceList` ASCII or binary, with a fast
// two-pass path for big ASCII bodies (face sizes first, then every vertex label straight into
// place), and `faceCompactList` (offsets and flat labels, two label lists).
#include "meshmorph/io/foam_face_lists.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>

#include "meshmorph/io/foam_list_binary.h"
#include "meshmorph/io/foam_list_kernels.h"
#include "meshmorph/io/foam_lists.h"

namespace meshmorph::io
{

namespace list_detail
{

namespace
{

ParseError too_many_vertex_labels(const FoamTokenizer& tok, const ListStart& start,
                                  const std::string& what)
{
    return tok.error_at(start.line,
                        "list '" + what + "' has more vertex labels than a label can count");
}

// The declared size `k` of face i: not negative, and not more vertices than the rest of the
// file can hold.
void check_face_size(const FoamTokenizer& tok, std::int64_t k, std::size_t i,
                     const std::string& what)
{
    const std::size_t line = tok.line();
    if (k < 0)
        throw tok.error_at(line, "face " + size_text(i) + " of '" + what + "' has negative size " +
                                     std::to_string(k));
    if (static_cast<std::size_t>(k) > remaining(tok) / min_chars_label + 1)
        throw tok.error_at(line, "face " + size_text(i) + " of '" + what + "' declares " +
                                     std::to_string(k) +
                                     " vertices, more than the rest of the file can hold");
}

// The closing bracket of an ASCII face of size k.
void expect_face_close(FoamTokenizer& tok, char close, std::int64_t k, std::size_t i,
                       const std::string& what)
{
    tok.skip_whitespace_and_comments();
    if (tok.offset() < tok.buffer().size() && tok.buffer()[tok.offset()] == close)
    {
        tok.expect(close);
        return;
    }
    const FoamToken& t = tok.peek();
    throw tok.error_at(t.line, "face " + size_text(i) + " of '" + what + "' has more than " +
                                   std::to_string(k) + " vertices (found " + t.describe() + ")");
}

// Whether a line starting at p begins a face: digits immediately followed by '('. Lines
// inside a face written over several lines (more than 10 vertices) hold a lone number or
// bracket, so such a line is always a face start.
bool is_face_start(const char* p, const char* e)
{
    const char* q = p;
    while (q < e && static_cast<unsigned>(*q - '0') < 10u)
        ++q;
    return q > p && q < e && *q == '(';
}

// The boundaries of the chunks of a faceList body [body_begin, body_end): about
// chunk_count() chunks when worthwhile, else one. Chunks start at face starts (see
// is_face_start), so each can be parsed alone.
std::vector<std::size_t> face_chunk_bounds(const FoamTokenizer& tok, const ListReadOptions& options,
                                           std::size_t body_begin, std::size_t body_end)
{
    const std::string_view buf = tok.buffer();
    std::vector<std::size_t> bounds{body_begin};
    if (worth_parallel(tok, options))
    {
        const int parts = chunk_count();
        const std::size_t len = body_end - body_begin;
        for (int k = 1; k < parts; ++k)
        {
            std::size_t pos = std::max(bounds.back(), body_begin + len * k / parts);
            while (pos < body_end)
            {
                const void* nl = std::memchr(buf.data() + pos, '\n', body_end - pos);
                if (!nl)
                {
                    pos = body_end;
                    break;
                }
                pos = static_cast<std::size_t>(static_cast<const char*>(nl) - buf.data()) + 1;
                if (is_face_start(buf.data() + pos, buf.data() + body_end))
                    break;
            }
            if (pos >= body_end)
                break;
            bounds.push_back(pos);
        }
    }
    bounds.push_back(body_end);
    return bounds;
}

// Pass 1: the face sizes of each chunk (the number before each '('), so that pass 2 can
// place every vertex label directly, with the flat list allocated once. False at anything
// unusual, or when the chunks do not hold `n_faces` faces in all.
bool read_face_sizes(std::string_view buf, const std::vector<std::size_t>& bounds,
                     std::size_t n_faces, std::vector<std::vector<Index>>& sizes)
{
    const std::size_t n_chunks = bounds.size() - 1;
    sizes.assign(n_chunks, {});
    std::vector<char> ok(n_chunks, 1);
#pragma omp parallel for schedule(dynamic, 1) if (n_chunks > 1)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(n_chunks); ++k)
    {
        const char* p = buf.data() + bounds[k];
        const char* const e = buf.data() + bounds[k + 1];
        std::vector<Index>& local = sizes[k];
        // One chunk: reserve the offsets' final size so they can take over this buffer.
        local.reserve(n_chunks == 1 ? n_faces + 1 : static_cast<std::size_t>(e - p) / 12 + 16);
        for (;;)
        {
            p = fast::skip_space(p, e);
            if (p == e)
                break;
            Index n = 0;
            if (!fast::label(p, e, n) || n < 0 || !fast::expect(p, e, '('))
            {
                ok[k] = 0;
                break;
            }
            // Faces are short: a plain loop beats a memchr call per face.
            const char* const open = p;
            while (p < e && *p != ')')
                ++p;
            // The declared size must fit between the brackets (a hostile size must not
            // become a huge allocation below).
            if (p == e || static_cast<std::size_t>(n) > static_cast<std::size_t>(p - open) / 2 + 1)
            {
                ok[k] = 0;
                break;
            }
            ++p;
            local.push_back(n);
        }
    }
    if (std::find(ok.begin(), ok.end(), 0) != ok.end())
        return false;
    std::size_t total = 0;
    for (const std::vector<Index>& local : sizes)
        total += local.size();
    return total == n_faces;
}

// The offsets from the sizes of a single chunk, reusing its buffer (no second nFaces array).
void offsets_from_one_chunk(const FoamTokenizer& tok, const ListStart& start,
                            const std::string& what, std::vector<Index>& sizes, CompactList& faces)
{
    sizes.insert(sizes.begin(), 0);
    faces.offsets = std::move(sizes);
    std::size_t running = 0;
    for (std::size_t i = 1; i < faces.offsets.size(); ++i)
    {
        running += static_cast<std::size_t>(faces.offsets[i]);
        if (running > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
            throw too_many_vertex_labels(tok, start, what);
        faces.offsets[i] = static_cast<Index>(running);
    }
}

// The offsets from the sizes of several chunks (freeing each as it is used); `first[k]` is
// set to the index of chunk k's first face.
void offsets_from_chunks(const FoamTokenizer& tok, const ListStart& start, const std::string& what,
                         std::vector<std::vector<Index>>& sizes, CompactList& faces,
                         std::vector<std::size_t>& first)
{
    faces.offsets.resize(start.size + 1);
    faces.offsets[0] = 0;
    std::size_t flat = 0;
    std::size_t f = 0;
    for (std::size_t k = 0; k < sizes.size(); ++k)
    {
        first[k] = f;
        for (Index n : sizes[k])
        {
            flat += static_cast<std::size_t>(n);
            if (flat > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
                throw too_many_vertex_labels(tok, start, what);
            faces.offsets[++f] = static_cast<Index>(flat);
        }
        std::vector<Index>().swap(sizes[k]);
    }
    first[sizes.size()] = f;
}

// The offsets of all faces from their sizes, and the flat vertex list allocated to its final
// size. Returns the index of each chunk's first face (and the face count last).
std::vector<std::size_t> place_faces(const FoamTokenizer& tok, const ListStart& start,
                                     const std::string& what,
                                     std::vector<std::vector<Index>>& sizes, CompactList& faces)
{
    const std::size_t n_chunks = sizes.size();
    std::vector<std::size_t> first(n_chunks + 1, 0);
    if (n_chunks == 1)
    {
        offsets_from_one_chunk(tok, start, what, sizes[0], faces);
        first[1] = start.size;
    }
    else
        offsets_from_chunks(tok, start, what, sizes, faces, first);
    sizes.clear();
    faces.values.resize(static_cast<std::size_t>(faces.offsets.back()));
    return first;
}

// Pass 2: the labels, straight into place (the declared sizes are checked again).
bool read_face_labels(std::string_view buf, const std::vector<std::size_t>& bounds,
                      const std::vector<std::size_t>& first, CompactList& faces)
{
    const std::size_t n_chunks = bounds.size() - 1;
    std::vector<char> ok(n_chunks, 1);
#pragma omp parallel for schedule(dynamic, 1) if (n_chunks > 1)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(n_chunks); ++k)
    {
        const char* p = buf.data() + bounds[k];
        const char* const e = buf.data() + bounds[k + 1];
        for (std::size_t i = first[k]; i < first[k + 1] && ok[k]; ++i)
            ok[k] = fast::face_into(p, e, faces.values.data() + faces.offsets[i],
                                    faces.offsets[i + 1] - faces.offsets[i]);
        if (ok[k] && fast::skip_space(p, e) != e)
            ok[k] = 0;
    }
    return std::find(ok.begin(), ok.end(), 0) == ok.end();
}

// Fast path for an ASCII faceList body (`k(v…)` elements, one bracket level), in parallel
// chunks when worthwhile. Returns false (nothing consumed) at anything unusual, so that the
// tokenizer re-parses and reports the precise error.
bool parse_faces_fast(FoamTokenizer& tok, const ListStart& start, CompactList& faces,
                      const ListReadOptions& options)
{
    const std::string_view buf = tok.buffer();
    const std::size_t body_begin = tok.offset();
    const std::size_t body_end = list_body_end(tok, 1);
    if (body_end == std::string_view::npos)
        return false;
    const std::vector<std::size_t> bounds = face_chunk_bounds(tok, options, body_begin, body_end);
    std::vector<std::vector<Index>> sizes;
    if (!read_face_sizes(buf, bounds, start.size, sizes))
        return false;
    const std::vector<std::size_t> first = place_faces(tok, start, options.what, sizes, faces);
    if (!read_face_labels(buf, bounds, first, faces))
    {
        faces.clear();
        return false;
    }
    tok.read_raw(body_end - body_begin);
    expect_close(tok, start, options.what, "face");
    return true;
}

// `N{face}`: one face repeated.
CompactList read_uniform_faces(FoamTokenizer& tok, const FoamHeader& header, const ListStart& start,
                               const ListReadOptions& options)
{
    std::vector<Index> one;
    if (header.is_binary())
        read_binary_face(tok, header, one, 0, options.what);
    else
        read_ascii_face(tok, one, start, 0, options.what);
    expect_close(tok, start, options.what, "face");
    CompactList faces;
    faces.offsets.reserve(start.size + 1);
    faces.values.reserve(start.size * one.size());
    for (std::size_t i = 0; i < start.size; ++i)
        faces.push_back(std::span<const Index>(one));
    return faces;
}

// Faces one by one with the tokenizer (or binary blocks), sized or unsized.
void read_faces_one_by_one(FoamTokenizer& tok, const FoamHeader& header, const ListStart& start,
                           const ListReadOptions& options, CompactList& faces)
{
    if (start.has_size)
    {
        faces.offsets.reserve(start.size + 1);
        faces.values.reserve(start.size * 4);
    }
    for (std::size_t i = 0; !start.has_size || i < start.size; ++i)
    {
        if (!start.has_size)
        {
            tok.skip_whitespace_and_comments();
            if (tok.offset() < tok.buffer().size() && tok.buffer()[tok.offset()] == ')')
                break;
        }
        if (header.is_binary())
            read_binary_face(tok, header, faces.values, i, options.what);
        else
            read_ascii_face(tok, faces.values, start, i, options.what);
        if (faces.values.size() > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
            throw too_many_vertex_labels(tok, start, options.what);
        faces.offsets.push_back(static_cast<Index>(faces.values.size()));
    }
}

CompactList read_face_list_plain(FoamTokenizer& tok, const FoamHeader& header,
                                 const ListReadOptions& options)
{
    const ListStart start = read_list_start(tok, header, options, min_chars_face, 0);
    CompactList faces;
    if (start.open == 0)
        return faces;
    if (start.open == '{')
        return read_uniform_faces(tok, header, start, options);
    if (start.has_size && !header.is_binary() && parse_faces_fast(tok, start, faces, options))
        return faces;
    read_faces_one_by_one(tok, header, start, options, faces);
    expect_close(tok, start, options.what, "face");
    if (options.expected_size && static_cast<std::size_t>(faces.size()) != *options.expected_size)
        throw tok.error_at(start.line, "list '" + options.what + "' has " +
                                           size_text(faces.size()) + " faces, expected " +
                                           size_text(*options.expected_size));
    return faces;
}

// faceCompactList: the offsets list (nFaces + 1, starting at 0, non-decreasing).
std::vector<Index> read_face_offsets(FoamTokenizer& tok, const FoamHeader& header,
                                     const ListReadOptions& options)
{
    ListReadOptions offsets_options = options;
    offsets_options.what = options.what + " offsets";
    if (options.expected_size)
        offsets_options.expected_size = *options.expected_size + 1;
    tok.skip_whitespace_and_comments();
    const std::size_t offsets_line = tok.line();
    const std::size_t offsets_offset = tok.offset();
    std::vector<Index> offsets = read_label_list(tok, header, offsets_options);
    const auto offsets_error = [&](const std::string& msg)
    {
        if (header.is_binary())
            return binary_error(tok, offsets_line, offsets_offset, offsets_options.what, msg);
        return tok.error_at(offsets_line, "list '" + offsets_options.what + "': " + msg);
    };
    if (offsets.empty())
        offsets.push_back(0); // zero faces may be written as an empty offsets list
    if (offsets[0] != 0)
        throw offsets_error("first offset is " + std::to_string(offsets[0]) + ", expected 0");
    for (std::size_t i = 1; i < offsets.size(); ++i)
        if (offsets[i] < offsets[i - 1])
            throw offsets_error("offsets decrease at face " + size_text(i - 1) + " (" +
                                std::to_string(offsets[i - 1]) + " then " +
                                std::to_string(offsets[i]) + ")");
    return offsets;
}

} // namespace

void read_ascii_face(FoamTokenizer& tok, std::vector<Index>& values, const ListStart& start,
                     std::size_t i, const std::string& what)
{
    std::int64_t k;
    if (!tok.read_label(k))
        throw_short_list(tok, start, i, what, "a face 'n(v0 v1 ...)'");
    check_face_size(tok, k, i, what);
    tok.skip_whitespace_and_comments();
    const bool uniform = tok.offset() < tok.buffer().size() && tok.buffer()[tok.offset()] == '{';
    tok.expect(uniform ? '{' : '(');
    const std::size_t n = uniform ? 1 : static_cast<std::size_t>(k);
    const std::size_t base = values.size();
    for (std::size_t j = 0; j < n; ++j)
    {
        std::int64_t v;
        if (!tok.read_label(v))
        {
            const FoamToken& t = tok.peek();
            throw tok.error_at(t.line, "face " + size_text(i) + " of '" + what + "' of size " +
                                           std::to_string(k) +
                                           ": expected a vertex label but found " + t.describe());
        }
        values.push_back(to_label(v, tok, what));
    }
    if (uniform)
        values.insert(values.end(), static_cast<std::size_t>(k) - 1, values[base]);
    expect_face_close(tok, uniform ? '}' : ')', k, i, what);
}

void read_binary_face(FoamTokenizer& tok, const FoamHeader& header, std::vector<Index>& values,
                      std::size_t i, const std::string& what)
{
    ListReadOptions face_options;
    face_options.what = what + "[" + size_text(i) + "]";
    face_options.max_uniform_size = 1u << 20;
    const ListStart start = read_list_start(tok, header, face_options, min_chars_label,
                                            static_cast<std::size_t>(header.label_bytes));
    if (start.open == 0)
        return;
    const std::size_t n = start.open == '{' ? 1 : start.size;
    const std::size_t data_offset = tok.offset();
    const std::string_view raw = tok.read_raw(n * static_cast<std::size_t>(header.label_bytes));
    const std::size_t base = values.size();
    values.resize(base + n);
    decode_labels(raw, header.label_bytes, values.data() + base, n, tok, start, data_offset,
                  face_options.what);
    expect_binary_close(tok, start, face_options.what, data_offset, start.open == '{' ? '}' : ')');
    if (start.open == '{')
        values.insert(values.end(), start.size - 1, values[base]);
}

} // namespace list_detail

CompactList read_face_list(FoamTokenizer& tok, const FoamHeader& header, bool compact,
                           const ListReadOptions& options)
{
    if (!compact)
        return list_detail::read_face_list_plain(tok, header, options);

    // faceCompactList: offsets (nFaces + 1) then flat labels.
    CompactList faces;
    faces.offsets = list_detail::read_face_offsets(tok, header, options);
    ListReadOptions flat_options = options;
    flat_options.what = options.what + " vertex labels";
    flat_options.expected_size = static_cast<std::size_t>(faces.offsets.back());
    faces.values = read_label_list(tok, header, flat_options);
    return faces;
}

} // namespace meshmorph::io
