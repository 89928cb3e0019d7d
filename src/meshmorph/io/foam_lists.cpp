// SPDX-License-Identifier: GPL-3.0-or-later
// Fast list readers/writers. The hot loops use the tokenizer's in-place number readers;
// large ASCII lists are split at line boundaries and parsed by OpenMP threads.
#include "meshmorph/io/foam_lists.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <type_traits>

#include <cstdlib>

#include <omp.h>

namespace meshmorph::io
{

static_assert(std::endian::native == std::endian::little,
              "binary OpenFOAM files are little-endian; big-endian hosts are not supported");

namespace
{

// Smallest number of characters an ASCII element can take (with its separator), used to
// reject declared sizes the remaining text cannot possibly hold.
constexpr std::size_t min_chars_label = 2;  // "0 "
constexpr std::size_t min_chars_vector = 7; // "(0 0 0)"
constexpr std::size_t min_chars_face = 8;   // "3(0 1 2)"

// Lists at least this long (in bytes of text) are parsed in parallel.
constexpr std::size_t parallel_min_bytes = std::size_t(1) << 20;

std::string size_text(std::size_t n)
{
    return std::to_string(n);
}

std::size_t remaining(const FoamTokenizer& tok)
{
    return tok.buffer().size() - tok.offset();
}

ParseError binary_error(const FoamTokenizer& tok, std::size_t line, std::size_t byte_offset,
                        const std::string& what, const std::string& msg)
{
    return tok.error_at(line, "binary list '" + what + "' at byte offset " +
                                  std::to_string(byte_offset) + ": " + msg);
}

// A label read as int64 converted to the list's label type L (Index, or int64 for
// dictionary values), range-checked when L is narrower.
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

// What starts a list: its declared size (or none for `( … )`), and the bracket.
struct ListStart
{
    bool has_size = false;
    std::size_t size = 0;
    char open = '('; // '(' , '{' (uniform), or 0 for an empty binary list without brackets
    std::size_t line = 0;
};

// Reads `N` and the opening bracket (ASCII or binary), validating N against the bytes left.
ListStart read_list_start(FoamTokenizer& tok, const FoamHeader& header,
                          const ListReadOptions& options, std::size_t ascii_min_chars,
                          std::size_t binary_element_bytes)
{
    ListStart start;
    tok.skip_whitespace_and_comments();
    start.line = tok.line();
    std::int64_t n = 0;
    if (tok.read_label(n))
    {
        if (n < 0)
            throw tok.error_at(start.line, "negative size " + std::to_string(n) + " of list '" +
                                               options.what + "'");
        start.has_size = true;
        start.size = static_cast<std::size_t>(n);
        if (options.expected_size && *options.expected_size != start.size)
            throw tok.error_at(start.line, "list '" + options.what + "' has size " +
                                               size_text(start.size) + ", expected " +
                                               size_text(*options.expected_size));
        if (header.is_binary() && binary_element_bytes > 0 && start.size == 0)
        {
            // OpenFOAM writes an empty binary list as `0` alone; accept `0()` too.
            start.open = 0;
            if (tok.peek().is_punct('('))
            {
                tok.expect('(');
                tok.expect(')');
            }
            return start;
        }
        if (start.size == 0 && !tok.peek().is_punct('(') && !tok.peek().is_punct('{'))
        {
            // `0` alone: the binary spelling of an empty list, accepted in ASCII too.
            start.open = 0;
            return start;
        }
    }
    const FoamToken& t = tok.peek();
    if (t.is_punct('('))
        start.open = '(';
    else if (t.is_punct('{') && start.has_size)
        start.open = '{';
    else
        throw tok.error_at(t.line, std::string("expected ") +
                                       (start.has_size ? "'(' or '{'" : "a list size or '('") +
                                       " for list '" + options.what + "' but found " +
                                       t.describe());
    tok.expect(start.open);
    if (!start.has_size && header.is_binary() && binary_element_bytes > 0)
        throw tok.error_at(start.line, "binary list '" + options.what + "' has no size");

    if (start.open == '{')
    {
        const std::size_t limit =
            options.expected_size ? *options.expected_size : options.max_uniform_size;
        if (start.size > limit)
            throw tok.error_at(start.line, "uniform list '" + options.what + "' of size " +
                                               size_text(start.size) +
                                               " exceeds the plausible size " + size_text(limit));
        return start;
    }
    if (start.has_size)
    {
        const std::size_t left = remaining(tok);
        if (header.is_binary() && binary_element_bytes > 0)
        {
            if (start.size > left / binary_element_bytes)
                throw binary_error(
                    tok, start.line, tok.offset(), options.what,
                    "declared size " + size_text(start.size) + " needs " +
                        (start.size > std::numeric_limits<std::size_t>::max() / binary_element_bytes
                             ? std::string("more")
                             : size_text(start.size * binary_element_bytes)) +
                        " bytes but only " + size_text(left) + " remain (truncated file?)");
        }
        else if (start.size > left / ascii_min_chars + 1)
            throw tok.error_at(start.line, "list '" + options.what + "' declares " +
                                               size_text(start.size) +
                                               " elements but the rest of the file is only " +
                                               size_text(left) + " bytes");
    }
    return start;
}

// After a binary block: the closing bracket must follow immediately.
void expect_binary_close(FoamTokenizer& tok, const ListStart& start, const std::string& what,
                         std::size_t data_offset, char close = ')')
{
    const std::size_t at = tok.offset();
    if (at < tok.buffer().size() && tok.buffer()[at] == close)
    {
        tok.expect(close);
        return;
    }
    throw binary_error(tok, start.line, at, what,
                       std::string("expected '") + close + "' after " + size_text(start.size) +
                           " elements (" + size_text(at - data_offset) +
                           " bytes) of binary data; the data may be ASCII under a binary "
                           "header, use other sizes than the arch says, or be truncated");
}

template <class Int, class L>
void decode_labels_as(std::string_view raw, L* out, std::size_t n, const FoamTokenizer& tok,
                      const ListStart& start, std::size_t data_offset, const std::string& what)
{
    if constexpr (sizeof(Int) == sizeof(L))
    {
        std::memcpy(out, raw.data(), n * sizeof(L));
    }
    else
    {
        for (std::size_t i = 0; i < n; ++i)
        {
            Int v;
            std::memcpy(&v, raw.data() + i * sizeof(Int), sizeof(Int));
            if constexpr (sizeof(Int) > sizeof(L))
            {
                if (v < std::numeric_limits<L>::min() || v > std::numeric_limits<L>::max())
                    throw binary_error(tok, start.line, data_offset + i * sizeof(Int), what,
                                       "label " + std::to_string(v) + " does not fit in a " +
                                           std::to_string(8 * sizeof(L)) + "-bit label");
            }
            out[i] = static_cast<L>(v);
        }
    }
}

template <class L>
void decode_labels(std::string_view raw, int label_bytes, L* out, std::size_t n,
                   const FoamTokenizer& tok, const ListStart& start, std::size_t data_offset,
                   const std::string& what)
{
    if (label_bytes == 4)
        decode_labels_as<std::int32_t>(raw, out, n, tok, start, data_offset, what);
    else
        decode_labels_as<std::int64_t>(raw, out, n, tok, start, data_offset, what);
}

void decode_scalars(std::string_view raw, int scalar_bytes, double* out, std::size_t n)
{
    if (scalar_bytes == 8)
        std::memcpy(out, raw.data(), n * sizeof(double));
    else
        for (std::size_t i = 0; i < n; ++i)
        {
            float v;
            std::memcpy(&v, raw.data() + i * sizeof(float), sizeof(float));
            out[i] = static_cast<double>(v);
        }
}

// ---------------------------------------------------------------------------------------
// ASCII element parsing (also used per chunk by the parallel path).

[[noreturn]] void throw_short_list(FoamTokenizer& tok, const ListStart& start, std::size_t got,
                                   const std::string& what, const char* kind)
{
    const FoamToken& t = tok.peek();
    if (t.is_punct(start.open == '{' ? '}' : ')'))
        throw tok.error_at(t.line, "list '" + what + "' ends after " + size_text(got) +
                                       " elements but its size is " + size_text(start.size));
    throw tok.error_at(t.line, std::string("expected ") + kind + " (element " + size_text(got) +
                                   " of list '" + what + "') but found " + t.describe());
}

void expect_close(FoamTokenizer& tok, const ListStart& start, const std::string& what,
                  const char* kind)
{
    const char close = start.open == '{' ? '}' : ')';
    tok.skip_whitespace_and_comments();
    if (tok.offset() < tok.buffer().size() && tok.buffer()[tok.offset()] == close)
    {
        tok.expect(close);
        return;
    }
    const FoamToken& t = tok.peek();
    if (start.has_size && start.open == '(' && (t.is_number() || t.is_punct('(')))
        throw tok.error_at(t.line, "list '" + what + "' has more elements than its size " +
                                       size_text(start.size));
    throw tok.error_at(t.line, std::string("expected '") + close + "' closing list '" + what +
                                   "' of " + kind + "s but found " + t.describe());
}

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

// A chunk of an ASCII list body for parallel parsing: [begin, end) of the buffer, the
// index of its first element and its number of elements.
struct Chunk
{
    std::size_t begin = 0;
    std::size_t end = 0;
    std::size_t first = 0;
    std::size_t count = 0;
};

// Find the end of a list body: the position of its matching ')' for a flat list of
// numbers or of `(…)` elements nested one level, scanning raw characters. Returns npos if
// not found. Only called when the body holds no comments.
std::size_t find_list_end(std::string_view buf, std::size_t from, int element_depth)
{
    int depth = 0;
    const char* p = buf.data() + from;
    const char* const end = buf.data() + buf.size();
    for (; p < end; ++p)
    {
        const char c = *p;
        if (c == '(')
        {
            if (++depth > element_depth)
                return std::string_view::npos;
        }
        else if (c == ')')
        {
            if (depth == 0)
                return static_cast<std::size_t>(p - buf.data());
            --depth;
        }
    }
    return std::string_view::npos;
}

// Split [begin, end) into about `parts` chunks at newlines (vectors and numbers never span
// lines in the bodies the fast kernels accept).
std::vector<Chunk> split_lines(std::string_view buf, std::size_t begin, std::size_t end, int parts)
{
    std::vector<Chunk> chunks;
    const std::size_t len = end - begin;
    std::size_t pos = begin;
    for (int k = 0; k < parts && pos < end; ++k)
    {
        std::size_t stop = k + 1 == parts ? end : begin + len * (k + 1) / parts;
        if (stop < pos)
            stop = pos;
        if (stop < end)
        {
            const void* nl = std::memchr(buf.data() + stop, '\n', end - stop);
            stop =
                nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - buf.data()) + 1 : end;
        }
        chunks.push_back({pos, stop, 0, 0});
        pos = stop;
    }
    return chunks;
}

// Count whitespace-separated tokens in a comment-free chunk of numbers.
std::size_t count_tokens(std::string_view buf, const Chunk& c)
{
    std::size_t n = 0;
    bool in_token = false;
    for (std::size_t i = c.begin; i < c.end; ++i)
    {
        const char ch = buf[i];
        const bool space =
            ch == ' ' || ch == '\n' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v';
        if (!space && !in_token)
            ++n;
        in_token = !space;
    }
    return n;
}

std::size_t count_char(std::string_view buf, const Chunk& c, char ch)
{
    return static_cast<std::size_t>(std::count(buf.data() + c.begin, buf.data() + c.end, ch));
}

int chunk_count()
{
    return std::max(1, omp_get_max_threads()) * 4;
}

// ---------------------------------------------------------------------------------------
// Fast kernels for the bodies of big ASCII lists. They run over comment-free text only and
// return false at anything unexpected; the caller then re-parses with the tokenizer, which
// produces the precise error (file:line). Labels are parsed by a digit loop (faster than
// std::from_chars<long>), scalars by std::from_chars<double>.
namespace fast
{

inline bool is_space(char c)
{
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

inline bool is_delimiter(const char* p, const char* e)
{
    if (p == e)
        return true;
    const char c = *p;
    return is_space(c) || c == '(' || c == ')' || c == '{' || c == '}' || c == '[' || c == ']' ||
           c == ';' || c == ',' || c == '"';
}

inline const char* skip_space(const char* p, const char* e)
{
    while (p < e && is_space(*p))
        ++p;
    return p;
}

template <class L> bool label(const char*& p, const char* e, L& out)
{
    p = skip_space(p, e);
    bool negative = false;
    if (p < e && (*p == '-' || *p == '+'))
    {
        negative = *p == '-';
        ++p;
    }
    const char* const digits = p;
    std::uint64_t v = 0;
    while (p < e && static_cast<unsigned>(*p - '0') < 10u && p - digits < 19)
        v = v * 10 + static_cast<unsigned>(*p++ - '0');
    if (p == digits || !is_delimiter(p, e))
        return false;
    const std::int64_t s = negative ? -static_cast<std::int64_t>(v) : static_cast<std::int64_t>(v);
    if (s < std::numeric_limits<L>::min() || s > std::numeric_limits<L>::max())
        return false;
    out = static_cast<L>(s);
    return true;
}

inline bool scalar(const char*& p, const char* e, double& out)
{
    p = skip_space(p, e);
    if (p < e && *p == '+')
        ++p;
    const std::from_chars_result r = std::from_chars(p, e, out);
    if (r.ec != std::errc() || !is_delimiter(r.ptr, e))
        return false;
    p = r.ptr;
    return true;
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

// `k(v0 ... vk-1)` written to dst (which has room for exactly `k_expected` labels when
// k_expected >= 0; otherwise appended to `grow`).
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

inline bool face_append(const char*& p, const char* e, std::vector<Index>& values)
{
    Index k = 0;
    if (!label(p, e, k) || k < 0 || !expect(p, e, '('))
        return false;
    const std::size_t base = values.size();
    values.resize(base + static_cast<std::size_t>(k));
    for (Index j = 0; j < k; ++j)
        if (!label(p, e, values[base + static_cast<std::size_t>(j)]))
            return false;
    return expect(p, e, ')');
}

} // namespace fast

// Where the body of a sized ASCII list ends (its closing ')'), to split it into chunks.
// Usually the list is the last thing in its file, so the last ')' of the file (followed
// only by comments) closes it; otherwise the brackets are counted. npos if not found.
std::size_t list_body_end(const FoamTokenizer& tok, int element_depth)
{
    const std::string_view buf = tok.buffer();
    const std::size_t begin = tok.offset();
    const std::size_t last = buf.rfind(')');
    if (last != std::string_view::npos && last >= begin)
    {
        FoamTokenizer tail(buf.substr(last + 1), tok.path());
        try
        {
            if (tail.at_end())
                return last;
        }
        catch (const ParseError&)
        {
        }
    }
    return find_list_end(buf, begin, element_depth);
}

// Threads only pay off on idle cores: on a machine already busy (1-minute load average
// above cores - 1) the OpenMP team's waiting threads cost more than they gain (measured on
// a loaded 2-core machine: 2 threads 100 MB/s, 1 thread 185 MB/s on motorBike).
bool worth_parallel(const FoamTokenizer& tok, const ListReadOptions& options)
{
    if (options.force_parallel)
        return true;
    if (!options.parallel || tok.buffer().size() - tok.offset() < parallel_min_bytes ||
        omp_get_max_threads() < 2)
        return false;
    double load = 0;
    if (::getloadavg(&load, 1) == 1 && load > omp_get_num_procs() - 1)
        return false;
    return true;
}

// Parse `n` fixed-size elements of a list body with the fast kernel `parse_one(p, e, i)`,
// in parallel chunks when worthwhile (`count_chunk` counts the elements of a chunk).
// On success advances the tokenizer past the body and the closing bracket.
template <class ParseOne, class CountChunk>
bool parse_fast(FoamTokenizer& tok, const ListStart& start, const ListReadOptions& options,
                int element_depth, ParseOne parse_one, CountChunk count_chunk, const char* kind)
{
    const std::string_view buf = tok.buffer();
    const std::size_t body_begin = tok.offset();
    const std::size_t n = start.size;
    bool ok = true;
    // Comments or uniform sub-lists make a kernel fail (and the tokenizer take over), so a
    // chunk boundary inside a comment cannot go unnoticed.
    std::size_t body_end =
        worth_parallel(tok, options) ? list_body_end(tok, element_depth) : std::string_view::npos;
    std::vector<Chunk> chunks;
    if (body_end != std::string_view::npos)
    {
        chunks = split_lines(buf, body_begin, body_end, chunk_count());
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
    }
    if (!chunks.empty())
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
        ok = std::find(chunk_ok.begin(), chunk_ok.end(), 0) == chunk_ok.end();
    }
    else
    {
        const char* p = buf.data() + body_begin;
        const char* const e = buf.data() + buf.size();
        for (std::size_t i = 0; i < n && ok; ++i)
            ok = parse_one(p, e, i);
        p = fast::skip_space(p, e);
        ok = ok && p < e && *p == ')';
        body_end = static_cast<std::size_t>(p - buf.data());
    }
    if (!ok)
        return false;
    tok.read_raw(body_end - body_begin);
    expect_close(tok, start, options.what, kind);
    return true;
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

// Faces: read one ASCII face `k(v0 … vk-1)` (or `k{v}`) appending to values.
void read_ascii_face(FoamTokenizer& tok, std::vector<Index>& values, const ListStart& start,
                     std::size_t i, const std::string& what)
{
    std::int64_t k;
    if (!tok.read_label(k))
        throw_short_list(tok, start, i, what, "a face 'n(v0 v1 ...)'");
    const std::size_t line = tok.line();
    if (k < 0)
        throw tok.error_at(line, "face " + size_text(i) + " of '" + what + "' has negative size " +
                                     std::to_string(k));
    if (static_cast<std::size_t>(k) > remaining(tok) / min_chars_label + 1)
        throw tok.error_at(line, "face " + size_text(i) + " of '" + what + "' declares " +
                                     std::to_string(k) +
                                     " vertices, more than the rest of the file can hold");
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
    tok.skip_whitespace_and_comments();
    const char close = uniform ? '}' : ')';
    if (tok.offset() < tok.buffer().size() && tok.buffer()[tok.offset()] == close)
    {
        tok.expect(close);
        return;
    }
    const FoamToken& t = tok.peek();
    throw tok.error_at(t.line, "face " + size_text(i) + " of '" + what + "' has more than " +
                                   std::to_string(k) + " vertices (found " + t.describe() + ")");
}

// Binary faceList: each face its own binary label block.
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
    // Chunks start at face starts (see is_face_start), so each can be parsed alone.
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
    const std::size_t n_chunks = bounds.size() - 1;

    // Pass 1: the face sizes of each chunk (the number before each '('), so that pass 2
    // can place every vertex label directly, with the flat list allocated once.
    std::vector<std::vector<Index>> sizes(n_chunks);
    std::vector<char> ok(n_chunks, 1);
#pragma omp parallel for schedule(dynamic, 1) if (n_chunks > 1)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(n_chunks); ++k)
    {
        const char* p = buf.data() + bounds[k];
        const char* const e = buf.data() + bounds[k + 1];
        std::vector<Index>& local = sizes[k];
        // One chunk: reserve the offsets' final size so they can take over this buffer.
        local.reserve(n_chunks == 1 ? start.size + 1 : static_cast<std::size_t>(e - p) / 12 + 16);
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
    if (total != start.size)
        return false;
    if (n_chunks == 1)
    {
        // Reuse the sizes buffer for the offsets (no second nFaces array).
        sizes[0].insert(sizes[0].begin(), 0);
        faces.offsets = std::move(sizes[0]);
        std::size_t running = 0;
        for (std::size_t i = 1; i < faces.offsets.size(); ++i)
        {
            running += static_cast<std::size_t>(faces.offsets[i]);
            if (running > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
                throw tok.error_at(start.line,
                                   "list '" + options.what +
                                       "' has more vertex labels than a label can count");
            faces.offsets[i] = static_cast<Index>(running);
        }
        sizes.clear();
    }
    else
        faces.offsets.resize(start.size + 1);
    faces.offsets[0] = 0;
    std::vector<std::size_t> first(n_chunks + 1, 0);
    std::size_t flat = 0;
    std::size_t f = 0;
    for (std::size_t k = 0; k < sizes.size(); ++k)
    {
        first[k] = f;
        for (Index n : sizes[k])
        {
            flat += static_cast<std::size_t>(n);
            if (flat > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
                throw tok.error_at(start.line,
                                   "list '" + options.what +
                                       "' has more vertex labels than a label can count");
            faces.offsets[++f] = static_cast<Index>(flat);
        }
        std::vector<Index>().swap(sizes[k]);
    }
    if (n_chunks == 1)
    {
        f = start.size;
        flat = static_cast<std::size_t>(faces.offsets.back());
    }
    first[n_chunks] = f;
    faces.values.resize(flat);

    // Pass 2: the labels, straight into place (the declared sizes are checked again).
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
    if (std::find(ok.begin(), ok.end(), 0) != ok.end())
    {
        faces.clear();
        return false;
    }
    tok.read_raw(body_end - body_begin);
    expect_close(tok, start, options.what, "face");
    return true;
}

CompactList read_face_list_plain(FoamTokenizer& tok, const FoamHeader& header,
                                 const ListReadOptions& options)
{
    const ListStart start = read_list_start(tok, header, options, min_chars_face, 0);
    CompactList faces;
    if (start.open == 0)
        return faces;
    if (start.open == '{')
    {
        std::vector<Index> one;
        if (header.is_binary())
            read_binary_face(tok, header, one, 0, options.what);
        else
            read_ascii_face(tok, one, start, 0, options.what);
        expect_close(tok, start, options.what, "face");
        faces.offsets.reserve(start.size + 1);
        faces.values.reserve(start.size * one.size());
        for (std::size_t i = 0; i < start.size; ++i)
            faces.push_back(std::span<const Index>(one));
        return faces;
    }
    if (start.has_size && !header.is_binary() && parse_faces_fast(tok, start, faces, options))
        return faces;
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
            throw tok.error_at(start.line, "list '" + options.what +
                                               "' has more vertex labels than a label can count");
        faces.offsets.push_back(static_cast<Index>(faces.values.size()));
    }
    expect_close(tok, start, options.what, "face");
    if (options.expected_size && static_cast<std::size_t>(faces.size()) != *options.expected_size)
        throw tok.error_at(start.line, "list '" + options.what + "' has " +
                                           size_text(faces.size()) + " faces, expected " +
                                           size_text(*options.expected_size));
    return faces;
}

// ---------------------------------------------------------------------------------------
// Writing

void append_label_text(std::string& out, std::int64_t v)
{
    char buf[24];
    const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

template <class Int> void append_raw_labels(std::string& out, const std::vector<Index>& values)
{
    if constexpr (sizeof(Int) == sizeof(Index))
    {
        out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(Index));
    }
    else
    {
        const std::size_t base = out.size();
        out.resize(base + values.size() * sizeof(Int));
        for (std::size_t i = 0; i < values.size(); ++i)
        {
            const Int v = static_cast<Int>(values[i]);
            std::memcpy(out.data() + base + i * sizeof(Int), &v, sizeof(Int));
        }
    }
}

void append_binary_labels(std::string& out, const std::vector<Index>& values, int label_bytes)
{
    // OpenFOAM: nl << size << nl, then `(` raw `)` unless empty.
    out += '\n';
    append_label_text(out, static_cast<std::int64_t>(values.size()));
    out += '\n';
    if (values.empty())
        return;
    out += '(';
    if (label_bytes == 8)
        append_raw_labels<std::int64_t>(out, values);
    else
        append_raw_labels<std::int32_t>(out, values);
    out += ')';
}

// OpenFOAM's ASCII List layout for contiguous elements (List::writeList, shortListLen 10).
template <class Elem, class AppendOne>
void append_ascii_list(std::string& out, std::size_t n, Elem elem, AppendOne append_one,
                       bool allow_uniform)
{
    bool uniform = allow_uniform && n > 1;
    for (std::size_t i = 1; uniform && i < n; ++i)
        uniform = elem(i) == elem(0);
    if (uniform)
    {
        append_label_text(out, static_cast<std::int64_t>(n));
        out += '{';
        append_one(out, 0);
        out += '}';
        return;
    }
    if (n <= 10)
    {
        append_label_text(out, static_cast<std::int64_t>(n));
        out += '(';
        for (std::size_t i = 0; i < n; ++i)
        {
            if (i > 0)
                out += ' ';
            append_one(out, i);
        }
        out += ')';
        return;
    }
    out += '\n';
    append_label_text(out, static_cast<std::int64_t>(n));
    out += "\n(\n";
    for (std::size_t i = 0; i < n; ++i)
    {
        append_one(out, i);
        out += '\n';
    }
    out += ")\n";
}

} // namespace

ElementLocation locate_list_element(FoamTokenizer& tok, const FoamHeader& header, ListKind kind,
                                    std::size_t index)
{
    try
    {
        ListReadOptions options;
        options.what = "list";
        options.parallel = false;
        if (kind == ListKind::face_compact_value)
        {
            read_label_list(tok, header, options); // offsets
            kind = ListKind::label;
        }
        std::size_t element_bytes = 0;
        if (header.is_binary())
            element_bytes = kind == ListKind::label    ? header.label_bytes
                            : kind == ListKind::scalar ? header.scalar_bytes
                            : kind == ListKind::vector ? 3 * header.scalar_bytes
                                                       : 0;
        const ListStart start = read_list_start(tok, header, options,
                                                kind == ListKind::vector ? min_chars_vector
                                                : kind == ListKind::face ? min_chars_face
                                                                         : min_chars_label,
                                                element_bytes);
        if (start.open != '(' || (start.has_size && index >= start.size))
            return {};
        if (element_bytes > 0)
            return {start.line, tok.offset() + index * element_bytes};
        std::vector<Index> scratch;
        for (std::size_t i = 0; i < index; ++i)
        {
            std::int64_t l;
            double d;
            double v[3];
            switch (kind)
            {
            case ListKind::label:
                if (!tok.read_label(l))
                    return {};
                break;
            case ListKind::scalar:
                if (!tok.read_scalar(d))
                    return {};
                break;
            case ListKind::vector:
                tok.read_vector(v);
                break;
            case ListKind::face:
            case ListKind::face_compact_value:
                scratch.clear();
                if (header.is_binary())
                    read_binary_face(tok, header, scratch, i, options.what);
                else
                    read_ascii_face(tok, scratch, start, i, options.what);
                break;
            }
        }
        tok.skip_whitespace_and_comments();
        return {tok.line(), tok.offset()};
    }
    catch (const Error&)
    {
        return {};
    }
}

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

CompactList read_face_list(FoamTokenizer& tok, const FoamHeader& header, bool compact,
                           const ListReadOptions& options)
{
    if (!compact)
        return read_face_list_plain(tok, header, options);

    // faceCompactList: offsets (nFaces + 1) then flat labels.
    ListReadOptions offsets_options = options;
    offsets_options.what = options.what + " offsets";
    if (options.expected_size)
        offsets_options.expected_size = *options.expected_size + 1;
    tok.skip_whitespace_and_comments();
    const std::size_t offsets_line = tok.line();
    const std::size_t offsets_offset = tok.offset();
    CompactList faces;
    faces.offsets = read_label_list(tok, header, offsets_options);
    const auto offsets_error = [&](const std::string& msg)
    {
        if (header.is_binary())
            return binary_error(tok, offsets_line, offsets_offset, offsets_options.what, msg);
        return tok.error_at(offsets_line, "list '" + offsets_options.what + "': " + msg);
    };
    if (faces.offsets.empty())
        faces.offsets.push_back(0); // zero faces may be written as an empty offsets list
    if (faces.offsets[0] != 0)
        throw offsets_error("first offset is " + std::to_string(faces.offsets[0]) + ", expected 0");
    for (std::size_t i = 1; i < faces.offsets.size(); ++i)
        if (faces.offsets[i] < faces.offsets[i - 1])
            throw offsets_error("offsets decrease at face " + size_text(i - 1) + " (" +
                                std::to_string(faces.offsets[i - 1]) + " then " +
                                std::to_string(faces.offsets[i]) + ")");
    ListReadOptions flat_options = options;
    flat_options.what = options.what + " vertex labels";
    flat_options.expected_size = static_cast<std::size_t>(faces.offsets.back());
    faces.values = read_label_list(tok, header, flat_options);
    return faces;
}

void append_scalar(std::string& out, double value, int digits)
{
    char buf[40];
    const std::to_chars_result r =
        std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, digits);
    out.append(buf, r.ptr);
}

void append_label_list(std::string& out, const std::vector<Index>& values, FoamFormat format,
                       int label_bytes, bool allow_uniform)
{
    if (format == FoamFormat::binary)
    {
        append_binary_labels(out, values, label_bytes);
        return;
    }
    append_ascii_list(
        out, values.size(), [&](std::size_t i) { return values[i]; },
        [&](std::string& o, std::size_t i) { append_label_text(o, values[i]); }, allow_uniform);
}

void append_vector_list(std::string& out, const Points& values, FoamFormat format, int digits)
{
    const std::size_t n = static_cast<std::size_t>(values.rows());
    if (format == FoamFormat::binary)
    {
        out += '\n';
        append_label_text(out, static_cast<std::int64_t>(n));
        out += '\n';
        if (n == 0)
            return;
        out += '(';
        out.append(reinterpret_cast<const char*>(values.data()), n * 3 * sizeof(double));
        out += ')';
        return;
    }
    out.reserve(out.size() + n * (3 * (digits + 7) + 3) + 32);
    append_ascii_list(
        out, n,
        [&](std::size_t i)
        {
            return std::array<double, 3>{values(static_cast<Eigen::Index>(i), 0),
                                         values(static_cast<Eigen::Index>(i), 1),
                                         values(static_cast<Eigen::Index>(i), 2)};
        },
        [&](std::string& o, std::size_t i)
        {
            const Eigen::Index r = static_cast<Eigen::Index>(i);
            o += '(';
            append_scalar(o, values(r, 0), digits);
            o += ' ';
            append_scalar(o, values(r, 1), digits);
            o += ' ';
            append_scalar(o, values(r, 2), digits);
            o += ')';
        },
        true);
}

void append_face_list(std::string& out, const CompactList& faces, FoamFormat format,
                      int label_bytes)
{
    if (format == FoamFormat::binary)
    {
        append_binary_labels(out, faces.offsets, label_bytes);
        append_binary_labels(out, faces.values, label_bytes);
        return;
    }
    // faceList is not contiguous: multi-line unless it has at most one face.
    const Index n = faces.size();
    const auto append_face = [&](std::string& o, Index f)
    {
        const std::span<const Index> face = faces[f];
        append_ascii_list(
            o, face.size(), [&](std::size_t i) { return face[i]; },
            [&](std::string& s, std::size_t i) { append_label_text(s, face[i]); }, true);
    };
    if (n <= 1)
    {
        append_label_text(out, n);
        out += '(';
        if (n == 1)
            append_face(out, 0);
        out += ')';
        return;
    }
    out.reserve(out.size() + faces.values.size() * 8 + static_cast<std::size_t>(n) * 4);
    out += '\n';
    append_label_text(out, n);
    out += "\n(\n";
    for (Index f = 0; f < n; ++f)
    {
        append_face(out, f);
        out += '\n';
    }
    out += ")\n";
}

} // namespace meshmorph::io
