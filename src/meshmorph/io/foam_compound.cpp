// SPDX-License-Identifier: GPL-3.0-or-later
// Compound lists in dictionaries (List<label>, List<scalar>, ... ascii or binary).
#include "meshmorph/io/foam_dictionary.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <limits>

#include "meshmorph/core/log.h"
#include "meshmorph/io/foam_file.h"

namespace fs = std::filesystem;

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

template <class T> T load_le(const char* p)
{
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

} // namespace

// ---------------------------------------------------------------------------------------
// Compounds

bool is_compound_type(std::string_view word)
{
    bool ok = false;
    compound_kind(word, ok);
    return ok;
}

FoamCompound read_compound(FoamTokenizer& tok, const std::string& type_word,
                           const ParseOptions& options)
{
    bool ok = false;
    FoamCompound c;
    c.kind = compound_kind(type_word, ok);
    c.type_word = type_word;
    if (!ok)
        throw tok.error("unknown compound list type '" + type_word + "'");
    using Kind = FoamCompound::Kind;
    const std::string what = "the size of a " + type_word;

    if (options.binary && c.kind != Kind::word)
    {
        if (options.label_bytes != 4 && options.label_bytes != 8)
            throw tok.error("unsupported binary label size " + std::to_string(options.label_bytes));
        if (options.scalar_bytes != 4 && options.scalar_bytes != 8)
            throw tok.error("unsupported binary scalar size " +
                            std::to_string(options.scalar_bytes));
        if constexpr (std::endian::native != std::endian::little)
            throw tok.error("binary OpenFOAM data can only be read on a little-endian machine");
        tok.skip_whitespace_and_comments();
        const std::size_t size_line = tok.line();
        const std::int64_t n = tok.expect_size(what);
        if (n == 0)
        {
            // OpenFOAM writes an empty binary list as a bare `0`; accept `0()` too.
            if (tok.accept('('))
                tok.expect(')');
            return c;
        }
        std::size_t elem = 1;
        switch (c.kind)
        {
        case Kind::label:
            elem = static_cast<std::size_t>(options.label_bytes);
            break;
        case Kind::scalar:
            elem = static_cast<std::size_t>(options.scalar_bytes);
            break;
        case Kind::vector:
            elem = 3 * static_cast<std::size_t>(options.scalar_bytes);
            break;
        case Kind::boolean:
        case Kind::word:
            elem = 1;
            break;
        }
        tok.expect('(');
        const std::size_t remaining = tok.buffer().size() - tok.offset();
        if (static_cast<std::uint64_t>(n) > remaining / elem)
            throw tok.error_at(size_line, "binary " + type_word + " of " + std::to_string(n) +
                                              " elements needs " + std::to_string(n * elem) +
                                              " bytes but only " + std::to_string(remaining) +
                                              " remain (truncated file?)");
        const std::size_t count = static_cast<std::size_t>(n);
        const std::string_view raw = tok.read_raw(count * elem);
        const char* p = raw.data();
        switch (c.kind)
        {
        case Kind::label:
            c.labels.resize(count);
            for (std::size_t i = 0; i < count; ++i)
                c.labels[i] = options.label_bytes == 4 ? load_le<std::int32_t>(p + 4 * i)
                                                       : load_le<std::int64_t>(p + 8 * i);
            break;
        case Kind::boolean:
            c.labels.resize(count);
            for (std::size_t i = 0; i < count; ++i)
                c.labels[i] = p[i] != 0 ? 1 : 0;
            break;
        case Kind::scalar:
        case Kind::vector:
        {
            const std::size_t m = count * (c.kind == Kind::vector ? 3 : 1);
            c.scalars.resize(m);
            if (options.scalar_bytes == 8)
                std::memcpy(c.scalars.data(), p, m * 8);
            else
                for (std::size_t i = 0; i < m; ++i)
                    c.scalars[i] = load_le<float>(p + 4 * i);
            break;
        }
        case Kind::word:
            break;
        }
        tok.expect(')');
        return c;
    }

    // ASCII: `N(...)`, `N{v}` or `(...)`.
    const std::size_t start_line = tok.peek().line;
    std::int64_t n = -1;
    if (tok.peek().is_label())
        n = tok.expect_size(what);
    const FoamToken open = tok.next();
    const bool uniform = open.is_punct('{');
    if (!open.is_punct('(') && !(uniform && n >= 0))
        throw tok.error_at(open.line, "expected '(' " + std::string(n >= 0 ? "or '{' " : "") +
                                          "to start the " + type_word + " but found " +
                                          open.describe());
    const auto fail = [&](std::size_t index) -> ParseError
    {
        const FoamToken t = tok.next();
        return tok.error_at(t.line, "bad element " + std::to_string(index) + " of " + type_word +
                                        ": found " + t.describe());
    };
    const auto read_one = [&](std::size_t index)
    {
        switch (c.kind)
        {
        case Kind::label:
        {
            std::int64_t v = 0;
            if (!tok.read_label(v))
                throw fail(index);
            c.labels.push_back(v);
            break;
        }
        case Kind::boolean:
        {
            std::int64_t v = 0;
            if (tok.read_label(v))
            {
                if (v != 0 && v != 1)
                    throw tok.error("bad element " + std::to_string(index) + " of " + type_word +
                                    ": " + std::to_string(v) + " is not a bool (0 or 1)");
                c.labels.push_back(v);
                break;
            }
            const FoamToken t = tok.next();
            if (t.is_word("true") || t.is_word("on") || t.is_word("yes"))
                c.labels.push_back(1);
            else if (t.is_word("false") || t.is_word("off") || t.is_word("no"))
                c.labels.push_back(0);
            else
                throw tok.error_at(t.line, "bad element " + std::to_string(index) + " of " +
                                               type_word + ": found " + t.describe());
            break;
        }
        case Kind::scalar:
        {
            double v = 0;
            if (!tok.read_scalar(v))
                throw fail(index);
            c.scalars.push_back(v);
            break;
        }
        case Kind::vector:
        {
            double xyz[3];
            tok.read_vector(xyz);
            c.scalars.insert(c.scalars.end(), xyz, xyz + 3);
            break;
        }
        case Kind::word:
        {
            FoamToken t = tok.next();
            if (!t.is_word() && !t.is_string())
                throw tok.error_at(t.line, "bad element " + std::to_string(index) + " of " +
                                               type_word + ": found " + t.describe());
            c.words.push_back(std::move(t.text));
            break;
        }
        }
    };
    const auto reserve = [&](std::size_t count)
    {
        // Never trust a size for allocation beyond what the remaining text could hold.
        count = std::min<std::size_t>(count, tok.buffer().size() - tok.offset());
        if (c.kind == Kind::label || c.kind == Kind::boolean)
            c.labels.reserve(count);
        else if (c.kind == Kind::scalar)
            c.scalars.reserve(count);
        else if (c.kind == Kind::vector)
            c.scalars.reserve(3 * count);
    };
    if (uniform)
    {
        read_one(0);
        tok.expect('}');
        if (n > max_uniform_list_size)
            throw tok.error_at(start_line, "uniform " + type_word + " of " + std::to_string(n) +
                                               " elements exceeds the label range of this build");
        const std::size_t count = static_cast<std::size_t>(n);
        if (c.kind == Kind::word)
            c.words.assign(count, c.words.front());
        else if (c.kind == Kind::vector)
        {
            const double x = c.scalars[0], y = c.scalars[1], z = c.scalars[2];
            c.scalars.clear();
            c.scalars.reserve(3 * count);
            for (std::size_t i = 0; i < count; ++i)
                c.scalars.insert(c.scalars.end(), {x, y, z});
        }
        else if (c.kind == Kind::scalar)
            c.scalars.assign(count, c.scalars.front());
        else
            c.labels.assign(count, c.labels.front());
        return c;
    }
    if (n >= 0)
    {
        reserve(static_cast<std::size_t>(n));
        const auto too_short = [&](std::int64_t i)
        {
            return tok.error_at(start_line, type_word + " declares " + std::to_string(n) +
                                                " elements but has only " + std::to_string(i));
        };
        // Dedicated loops for the large contiguous kinds; the checks for a premature ')'
        // run only when an element fails to parse.
        if (c.kind == Kind::label)
        {
            std::int64_t v = 0;
            for (std::int64_t i = 0; i < n; ++i)
            {
                if (!tok.read_label(v))
                {
                    const char ch = tok.peek_char();
                    if (ch == ')' || ch == '\0')
                        throw too_short(i);
                    throw fail(static_cast<std::size_t>(i));
                }
                c.labels.push_back(v);
            }
        }
        else if (c.kind == Kind::scalar)
        {
            double v = 0;
            for (std::int64_t i = 0; i < n; ++i)
            {
                if (!tok.read_scalar(v))
                {
                    const char ch = tok.peek_char();
                    if (ch == ')' || ch == '\0')
                        throw too_short(i);
                    throw fail(static_cast<std::size_t>(i));
                }
                c.scalars.push_back(v);
            }
        }
        else if (c.kind == Kind::vector)
        {
            double xyz[3];
            for (std::int64_t i = 0; i < n; ++i)
            {
                const char ch = tok.peek_char();
                if (ch == ')' || ch == '\0')
                    throw too_short(i);
                tok.read_vector(xyz);
                c.scalars.insert(c.scalars.end(), xyz, xyz + 3);
            }
        }
        else
        {
            for (std::int64_t i = 0; i < n; ++i)
            {
                const char ch = tok.peek_char();
                if (ch == ')' || ch == '\0')
                    throw too_short(i);
                read_one(static_cast<std::size_t>(i));
            }
        }
        const FoamToken close = tok.next();
        if (!close.is_punct(')'))
            throw tok.error_at(close.line, type_word + " declares " + std::to_string(n) +
                                               " elements but has more (found " + close.describe() +
                                               " where ')' was expected)");
        return c;
    }
    for (std::size_t i = 0;; ++i)
    {
        const FoamToken& t = tok.peek();
        if (t.is_punct(')'))
        {
            tok.next();
            return c;
        }
        if (t.is_end())
            throw tok.error_at(open.line, "unterminated " + type_word + " (no closing ')')");
        read_one(i);
    }
}

} // namespace meshmorph::io
