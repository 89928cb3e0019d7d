// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The one lexer of OpenFOAM numbers (labels and scalars): where a number may start and
//! end, and how its spelling becomes an int64 or a double. The tokenizer
//! (io/foam_tokenizer.cpp) and the fast kernels of big ASCII lists (io/foam_list_kernels.h)
//! both use it, so that the rules are written once; its functions are inline because they
//! run once per number in the hot loops.
//!
//! The two callers accept slightly different spellings; the Dialect parameter keeps both:
//! - Where a number ends: for the tokenizer at the end, space, `( ) { } [ ] ; ,`, `"`, or the
//!   start of a comment (`//`, `/*`); for the list kernels the same but not at `/` (they run
//!   over comment-free text).
//! - Labels: a sign `+`/`-` then digits. Both read up to 18 digits in a loop; the tokenizer
//!   reads longer spellings with std::from_chars over the whole int64 range (out of range:
//!   not a label), the kernels refuse them (their caller re-parses with the tokenizer).
//! - Scalars: for the tokenizer a number must start like one (a digit, a sign then a digit or
//!   `.digit`, or `.digit`), so `nan` and `inf` are words. The kernels skip one leading `+`
//!   and take whatever std::from_chars reads: `nan`, `inf`, `infinity`, `-inf`, `+-1`.
//! - Out of the double range: the tokenizer's full token scan (convert_number_token) accepts
//!   underflow (denormal or zero, as strtod) and rejects overflow; the fast readers of both
//!   dialects reject both, and their callers re-parse with the full scan.
//!
//! A kernel that rejects a number makes its caller re-parse the list with the tokenizer,
//! which then reports the precise error; so the differences only show where the kernels
//! accept more: `nan`/`inf` in sized ASCII scalar and vector lists.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <system_error>

namespace meshmorph::io::number_lexer
{

//! Which caller's acceptance rules to apply (see the file comment).
enum class Dialect
{
    tokenizer,   //!< FoamTokenizer: numbers as tokens of the full syntax
    list_kernel, //!< the fast kernels of big ASCII lists: comment-free list bodies
};

//! Space as OpenFOAM's tokenizer counts it.
inline bool is_space(char c)
{
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

//! The punctuation tokens `( ) { } [ ] ; ,`.
inline bool is_punct(char c)
{
    switch (c)
    {
    case '(':
    case ')':
    case '{':
    case '}':
    case '[':
    case ']':
    case ';':
    case ',':
        return true;
    default:
        return false;
    }
}

inline bool is_digit(char c)
{
    return static_cast<unsigned>(c - '0') < 10u;
}

//! Whether the byte at p ends a number (or, for the tokenizer, a word): the end of input,
//! space, punctuation or `"`; for the tokenizer also the start of a comment.
template <Dialect D> inline bool ends_number(const char* p, const char* end)
{
    if (p == end)
        return true;
    const char c = *p;
    if (is_space(c) || is_punct(c) || c == '"')
        return true;
    if constexpr (D == Dialect::tokenizer)
        return c == '/' && p + 1 < end && (p[1] == '/' || p[1] == '*');
    else
        return false;
}

//! Whether the text at p looks like a number to the tokenizer: a digit, or a sign or a dot
//! followed by a digit (or a sign followed by `.digit`). `nan` and `inf` do not.
inline bool starts_number(const char* p, const char* end)
{
    if (p == end)
        return false;
    if (is_digit(*p))
        return true;
    if (*p == '-' || *p == '+')
    {
        ++p;
        if (p == end)
            return false;
        if (is_digit(*p))
            return true;
        return *p == '.' && p + 1 < end && is_digit(p[1]);
    }
    if (*p == '.')
        return p + 1 < end && is_digit(p[1]);
    return false;
}

//! One past the last character of the token starting at p (the next delimiter).
inline const char* token_end(const char* p, const char* end)
{
    while (!ends_number<Dialect::tokenizer>(p, end))
        ++p;
    return p;
}

//! \brief A label at p (no leading space), as the dialect reads it: on success stores it in
//! `value`, moves p past it and returns true; otherwise returns false with p unchanged
//! (the tokenizer dialect may have stored a number that is not followed by a delimiter).
template <Dialect D> inline bool lex_label(const char*& p, const char* end, std::int64_t& value)
{
    // Up to 18 digits cannot overflow an int64; longer spellings are range-checked by
    // std::from_chars (tokenizer) or refused here, so that the list kernel hands the list to
    // the tokenizer, whose error names the label (a 19-digit label used to wrap around).
    // Negation in unsigned arithmetic gives the two's-complement result without overflow.
    constexpr std::ptrdiff_t max_digits = 18;
    const char* q = p;
    const bool negative = q < end && *q == '-';
    if (q < end && (*q == '-' || *q == '+'))
        ++q;
    const char* const digits = q;
    std::uint64_t v = 0;
    while (q < end && q - digits < max_digits && is_digit(*q))
        v = 10 * v + static_cast<unsigned>(*q++ - '0');
    if (q > digits && ends_number<D>(q, end))
    {
        value = negative ? static_cast<std::int64_t>(0 - v) : static_cast<std::int64_t>(v);
        p = q;
        return true;
    }
    if constexpr (D == Dialect::tokenizer)
    {
        // Longer spellings: std::from_chars checks the int64 range.
        const char* const num = p < end && *p == '+' ? p + 1 : p;
        const std::from_chars_result r = std::from_chars(num, end, value);
        if (r.ec != std::errc() || !ends_number<D>(r.ptr, end) || r.ptr == num)
            return false;
        p = r.ptr;
        return true;
    }
    else
        return false;
}

//! \brief A scalar at p (no leading space; labels are scalars too), as the dialect reads it:
//! on success stores it, moves p past it and returns true. Returns false on anything else,
//! including a number out of the double range (the tokenizer's full scan decides those), with
//! p unchanged (`value` may have been stored when no delimiter follows the number).
template <Dialect D> inline bool lex_scalar(const char*& p, const char* end, double& value)
{
    if constexpr (D == Dialect::tokenizer)
    {
        if (!starts_number(p, end))
            return false;
    }
    const char* const num = p < end && *p == '+' ? p + 1 : p;
    const std::from_chars_result r = std::from_chars(num, end, value);
    if (r.ec != std::errc() || !ends_number<D>(r.ptr, end))
        return false;
    p = r.ptr;
    return true;
}

//! What the spelling of a whole number token is.
struct NumberToken
{
    enum class Kind
    {
        label,        //!< an integer that fits in int64
        scalar,       //!< any other number (also an integer beyond int64)
        malformed,    //!< not a number although it starts like one (`1.2.3`, `1e`)
        out_of_range, //!< a floating-point spelling beyond the double range (`1e999`)
    };
    Kind kind = Kind::malformed;
    std::int64_t label = 0;
    double scalar = 0.0; //!< for scalar and label (label converted)
};

//! \brief Converts the token [p, q) (which starts_number accepted and token_end delimited)
//! as the tokenizer does: an int64 when std::from_chars reads it whole, else a double.
//! Out of the double range: an integer spelling is read by strtod (beyond int64 it becomes a
//! scalar; beyond the double range, infinity), a floating-point spelling that underflows is
//! accepted (denormal or zero, as strtod does), one that overflows is out_of_range.
inline NumberToken convert_number_token(const char* p, const char* q)
{
    NumberToken n;
    const char* const num = (*p == '+') ? p + 1 : p;
    std::int64_t ival = 0;
    const std::from_chars_result ir = std::from_chars(num, q, ival);
    if (ir.ec == std::errc() && ir.ptr == q)
    {
        n.kind = NumberToken::Kind::label;
        n.label = ival;
        n.scalar = static_cast<double>(ival);
        return n;
    }
    double dval = 0.0;
    const std::from_chars_result dr = std::from_chars(num, q, dval);
    if (dr.ptr != q || (dr.ec != std::errc() && dr.ec != std::errc::result_out_of_range))
        return n; // malformed
    if (dr.ec == std::errc::result_out_of_range)
    {
        bool is_integer_spelling = true;
        for (const char* s = num; s < q; ++s)
            if (!is_digit(*s) && *s != '-')
                is_integer_spelling = false;
        dval = std::strtod(std::string(num, q).c_str(), nullptr);
        if (!is_integer_spelling && (dval == HUGE_VAL || dval == -HUGE_VAL))
        {
            n.kind = NumberToken::Kind::out_of_range;
            return n;
        }
    }
    n.kind = NumberToken::Kind::scalar;
    n.scalar = dval;
    return n;
}

} // namespace meshmorph::io::number_lexer
