// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal to the list readers (io/foam_lists.h): the fast path for the bodies of big
//! ASCII lists. It exists because the tokenizer, which builds precise errors, is several
//! times slower than a plain character loop over the hundreds of megabytes of a large
//! polyMesh. The kernels run over comment-free text only and return false at anything
//! unexpected; the caller then re-parses with the tokenizer, which produces the precise error
//! (file:line). Numbers are read by io/number_lexer.h (Dialect::list_kernel). Large bodies are
//! split at line boundaries into chunks parsed by OpenMP threads.
//!
//! The per-element kernels are inline, in this header, so that they are compiled into the
//! loops of the readers that include it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/io/foam_list_options.h"
#include "meshmorph/io/foam_list_start.h"
#include "meshmorph/io/foam_tokenizer.h"
#include "meshmorph/io/number_lexer.h"

namespace meshmorph::io::list_detail
{

//! A chunk of an ASCII list body for parallel parsing: [begin, end) of the buffer, the
//! index of its first element and its number of elements.
struct Chunk
{
    std::size_t begin = 0;
    std::size_t end = 0;
    std::size_t first = 0;
    std::size_t count = 0;
};

//! Split [begin, end) into about `parts` chunks at newlines (vectors and numbers never span
//! lines in the bodies the fast kernels accept).
std::vector<Chunk> split_lines(std::string_view buf, std::size_t begin, std::size_t end, int parts);

//! The number of chunks to split a list body into (a few per OpenMP thread).
int chunk_count();

//! \brief Where the body of a sized ASCII list ends (its closing ')'), to split it into
//! chunks: elements nest `element_depth` bracket levels. npos if not found.
std::size_t list_body_end(const FoamTokenizer& tok, int element_depth);

//! Whether to parse the list at the tokenizer's position in parallel chunks: only big lists,
//! and only when the machine has idle cores (or options.force_parallel).
bool worth_parallel(const FoamTokenizer& tok, const ListReadOptions& options);

//! Count whitespace-separated tokens in a comment-free chunk of numbers.
inline std::size_t count_tokens(std::string_view buf, const Chunk& c)
{
    std::size_t n = 0;
    bool in_token = false;
    for (std::size_t i = c.begin; i < c.end; ++i)
    {
        const bool space = number_lexer::is_space(buf[i]);
        if (!space && !in_token)
            ++n;
        in_token = !space;
    }
    return n;
}

inline std::size_t count_char(std::string_view buf, const Chunk& c, char ch)
{
    return static_cast<std::size_t>(std::count(buf.data() + c.begin, buf.data() + c.end, ch));
}

//! The per-element kernels: each reads one element at p (after optional space), advancing
//! p, or returns false.
namespace fast
{

using number_lexer::Dialect;

inline const char* skip_space(const char* p, const char* e)
{
    while (p < e && number_lexer::is_space(*p))
        ++p;
    return p;
}

template <class L> bool label(const char*& p, const char* e, L& out)
{
    p = skip_space(p, e);
    std::int64_t s = 0;
    if (!number_lexer::lex_label<Dialect::list_kernel>(p, e, s))
        return false;
    if (s < std::numeric_limits<L>::min() || s > std::numeric_limits<L>::max())
        return false;
    out = static_cast<L>(s);
    return true;
}

inline bool scalar(const char*& p, const char* e, double& out)
{
    p = skip_space(p, e);
    return number_lexer::lex_scalar<Dialect::list_kernel>(p, e, out);
}

inline bool expect(const char*& p, const char* e, char c)
{
    p = skip_space(p, e);
    if (p < e && *p == c)
    {
        ++p;
        return true;
    }
    return false;
}

inline bool vector(const char*& p, const char* e, double* xyz)
{
    return expect(p, e, '(') && scalar(p, e, xyz[0]) && scalar(p, e, xyz[1]) &&
           scalar(p, e, xyz[2]) && expect(p, e, ')');
}

//! `k(v0 ... vk-1)` written to dst, which has room for exactly `k_expected` labels.
inline bool face_into(const char*& p, const char* e, Index* dst, Index k_expected)
{
    Index k = 0;
    if (!label(p, e, k) || k != k_expected || !expect(p, e, '('))
        return false;
    for (Index j = 0; j < k; ++j)
        if (!label(p, e, dst[j]))
            return false;
    return expect(p, e, ')');
}

} // namespace fast

//! Split the body at the tokenizer's position into chunks of exactly `n` elements in all
//! (`count_chunk` counts the elements of a chunk); empty when not worthwhile, or when the
//! body's end cannot be found (then `body_end` is npos).
template <class CountChunk>
std::vector<Chunk> chunk_body(const FoamTokenizer& tok, const ListReadOptions& options,
                              int element_depth, std::size_t n, CountChunk count_chunk,
                              std::size_t& body_end)
{
    // Comments or uniform sub-lists make a kernel fail (and the tokenizer take over), so a
    // chunk boundary inside a comment cannot go unnoticed.
    body_end =
        worth_parallel(tok, options) ? list_body_end(tok, element_depth) : std::string_view::npos;
    if (body_end == std::string_view::npos)
        return {};
    std::vector<Chunk> chunks = split_lines(tok.buffer(), tok.offset(), body_end, chunk_count());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(chunks.size()); ++k)
        chunks[k].count = count_chunk(chunks[k]);
    std::size_t total = 0;
    for (Chunk& c : chunks)
    {
        c.first = total;
        total += c.count;
    }
    // Not exactly n elements: the guessed end was not this list's (a list inside a
    // dictionary, followed by more lists); the serial kernel finds the real one.
    if (total != n)
        chunks.clear();
    return chunks;
}

//! Parse the elements of `chunks` with `parse_one(p, e, i)` in OpenMP threads; true when
//! every chunk parsed whole.
template <class ParseOne>
bool parse_chunks(std::string_view buf, const std::vector<Chunk>& chunks, ParseOne parse_one)
{
    std::vector<char> chunk_ok(chunks.size(), 1);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(chunks.size()); ++k)
    {
        const Chunk& c = chunks[k];
        const char* p = buf.data() + c.begin;
        const char* const e = buf.data() + c.end;
        for (std::size_t i = 0; i < c.count && chunk_ok[k]; ++i)
            chunk_ok[k] = parse_one(p, e, c.first + i);
        if (chunk_ok[k] && fast::skip_space(p, e) != e)
            chunk_ok[k] = 0;
    }
    return std::find(chunk_ok.begin(), chunk_ok.end(), 0) == chunk_ok.end();
}

//! Parse `n` elements from `body_begin` with `parse_one(p, e, i)` in one thread, up to the
//! closing ')'; sets `body_end` to its position. True on success.
template <class ParseOne>
bool parse_serial(std::string_view buf, std::size_t body_begin, std::size_t n, ParseOne parse_one,
                  std::size_t& body_end)
{
    bool ok = true;
    const char* p = buf.data() + body_begin;
    const char* const e = buf.data() + buf.size();
    for (std::size_t i = 0; i < n && ok; ++i)
        ok = parse_one(p, e, i);
    p = fast::skip_space(p, e);
    ok = ok && p < e && *p == ')';
    body_end = static_cast<std::size_t>(p - buf.data());
    return ok;
}

//! \brief Parse the `start.size` fixed-size elements of a list body with the fast kernel
//! `parse_one(p, e, i)`, in parallel chunks when worthwhile (`count_chunk` counts the
//! elements of a chunk). On success advances the tokenizer past the body and the closing
//! bracket; on failure consumes nothing.
template <class ParseOne, class CountChunk>
bool parse_fast(FoamTokenizer& tok, const ListStart& start, const ListReadOptions& options,
                int element_depth, ParseOne parse_one, CountChunk count_chunk, const char* kind)
{
    const std::string_view buf = tok.buffer();
    const std::size_t body_begin = tok.offset();
    std::size_t body_end = std::string_view::npos;
    const std::vector<Chunk> chunks =
        chunk_body(tok, options, element_depth, start.size, count_chunk, body_end);
    const bool ok = chunks.empty() ? parse_serial(buf, body_begin, start.size, parse_one, body_end)
                                   : parse_chunks(buf, chunks, parse_one);
    if (!ok)
        return false;
    tok.read_raw(body_end - body_begin);
    expect_close(tok, start, options.what, kind);
    return true;
}

} // namespace meshmorph::io::list_detail
