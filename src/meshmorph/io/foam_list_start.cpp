// SPDX-License-Identifier: GPL-3.0-or-later
// How an OpenFOAM list starts and ends (io/foam_list_start.h): the declared size, the
// bracket, the checks of the size against the remaining input, and the shared messages.
#include "meshmorph/io/foam_list_start.h"

namespace meshmorph::io::list_detail
{

namespace
{

// Reads the declared size `N` if there is one, checking its sign and the expected size.
bool read_declared_size(FoamTokenizer& tok, const ListReadOptions& options, ListStart& start)
{
    std::int64_t n = 0;
    if (!tok.read_label(n))
        return false;
    if (n < 0)
        throw tok.error_at(start.line, "negative size " + std::to_string(n) + " of list '" +
                                           options.what + "'");
    start.has_size = true;
    start.size = static_cast<std::size_t>(n);
    if (options.expected_size && *options.expected_size != start.size)
        throw tok.error_at(start.line, "list '" + options.what + "' has size " +
                                           size_text(start.size) + ", expected " +
                                           size_text(*options.expected_size));
    return true;
}

// After a declared size of 0: the empty list without brackets (`0` alone), which ends the
// list (start.open = 0, returns true). An empty binary list also accepts `0()`.
bool read_bare_empty_list(FoamTokenizer& tok, bool binary, ListStart& start)
{
    if (start.size != 0)
        return false;
    if (binary)
    {
        // OpenFOAM writes an empty binary list as `0` alone; accept `0()` too.
        start.open = 0;
        if (tok.peek().is_punct('('))
        {
            tok.expect('(');
            tok.expect(')');
        }
        return true;
    }
    if (!tok.peek().is_punct('(') && !tok.peek().is_punct('{'))
    {
        // `0` alone: the binary spelling of an empty list, accepted in ASCII too.
        start.open = 0;
        return true;
    }
    return false;
}

// Reads the opening bracket: '(' or, after a size, '{' (uniform list).
void read_open_bracket(FoamTokenizer& tok, const ListReadOptions& options, bool binary,
                       ListStart& start)
{
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
    if (!start.has_size && binary)
        throw tok.error_at(start.line, "binary list '" + options.what + "' has no size");
}

// A uniform list `N{v}` is a few bytes for any N: N is bounded by the expected size or by
// options.max_uniform_size instead of by the input left.
void check_uniform_size(const FoamTokenizer& tok, const ListReadOptions& options,
                        const ListStart& start)
{
    const std::size_t limit =
        options.expected_size ? *options.expected_size : options.max_uniform_size;
    if (start.size > limit)
        throw tok.error_at(start.line, "uniform list '" + options.what + "' of size " +
                                           size_text(start.size) + " exceeds the plausible size " +
                                           size_text(limit));
}

// The declared size must fit in the input left: `binary_element_bytes` per element of a
// binary list (when non-zero), else at least `ascii_min_chars` per ASCII element.
void check_size_fits_input(const FoamTokenizer& tok, const ListReadOptions& options,
                           std::size_t ascii_min_chars, std::size_t binary_element_bytes,
                           const ListStart& start)
{
    const std::size_t left = remaining(tok);
    if (binary_element_bytes > 0)
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

} // namespace

ParseError binary_error(const FoamTokenizer& tok, std::size_t line, std::size_t byte_offset,
                        const std::string& what, const std::string& msg)
{
    return tok.error_at(line, "binary list '" + what + "' at byte offset " +
                                  std::to_string(byte_offset) + ": " + msg);
}

ListStart read_list_start(FoamTokenizer& tok, const FoamHeader& header,
                          const ListReadOptions& options, std::size_t ascii_min_chars,
                          std::size_t binary_element_bytes)
{
    ListStart start;
    tok.skip_whitespace_and_comments();
    start.line = tok.line();
    const bool binary = header.is_binary() && binary_element_bytes > 0;
    if (read_declared_size(tok, options, start) && read_bare_empty_list(tok, binary, start))
        return start;
    read_open_bracket(tok, options, binary, start);
    if (start.open == '{')
        check_uniform_size(tok, options, start);
    else if (start.has_size)
        check_size_fits_input(tok, options, ascii_min_chars, binary ? binary_element_bytes : 0,
                              start);
    return start;
}

void expect_binary_close(FoamTokenizer& tok, const ListStart& start, const std::string& what,
                         std::size_t data_offset, char close)
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

} // namespace meshmorph::io::list_detail
