// SPDX-License-Identifier: GPL-3.0-or-later
// Tokenizer for OpenFOAM's text syntax; numbers are recognised and converted in place by
// io/number_lexer.h (Dialect::tokenizer).
#include "meshmorph/io/foam_tokenizer.h"

#include <cstring>

#include "meshmorph/io/number_lexer.h"

namespace meshmorph::io
{

namespace
{

using number_lexer::Dialect;
using number_lexer::is_punct;
using number_lexer::is_space;
using number_lexer::starts_number;

std::string quote_text(std::string_view s)
{
    constexpr std::size_t max_len = 40;
    if (s.size() > max_len)
        return "'" + std::string(s.substr(0, max_len)) + "...'";
    return "'" + std::string(s) + "'";
}

} // namespace

std::string FoamToken::describe() const
{
    switch (type)
    {
    case TokenType::end:
        return "end of file";
    case TokenType::punctuation:
        return std::string("'") + punct + "'";
    case TokenType::word:
        return "word " + quote_text(text);
    case TokenType::string:
        return "string \"" + text.substr(0, 40) + (text.size() > 40 ? "...\"" : "\"");
    case TokenType::label:
        return "integer " + text;
    case TokenType::scalar:
        return "number " + text;
    }
    return "token";
}

FoamTokenizer::FoamTokenizer(std::string_view buffer, std::string path, std::size_t first_line)
    : buffer_(buffer), path_(std::move(path)), line_(first_line)
{
}

std::string_view FoamTokenizer::slice(std::size_t begin, std::size_t end) const
{
    if (begin > buffer_.size())
        begin = buffer_.size();
    if (end > buffer_.size())
        end = buffer_.size();
    if (end < begin)
        end = begin;
    return buffer_.substr(begin, end - begin);
}

ParseError FoamTokenizer::error(const std::string& msg) const
{
    return ParseError(path_, line_, msg);
}

ParseError FoamTokenizer::error_at(std::size_t line, const std::string& msg) const
{
    return ParseError(path_, line, msg);
}

void FoamTokenizer::discard_peek()
{
    has_peek_ = false;
}

void FoamTokenizer::skip_whitespace_and_comments()
{
    discard_peek();
    const char* const begin = buffer_.data();
    const char* p = begin + pos_;
    const char* const end = begin + buffer_.size();
    std::size_t line = line_;
    while (p < end)
    {
        const char c = *p;
        if (c == '\n')
        {
            ++line;
            ++p;
        }
        else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v')
            ++p;
        else if (c == '/' && p + 1 < end && p[1] == '/')
        {
            const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
            p = nl ? static_cast<const char*>(nl) : end;
        }
        else if (c == '/' && p + 1 < end && p[1] == '*')
        {
            const std::size_t start_line = line;
            p += 2;
            bool closed = false;
            while (p < end)
            {
                if (*p == '\n')
                    ++line;
                else if (*p == '*' && p + 1 < end && p[1] == '/')
                {
                    p += 2;
                    closed = true;
                    break;
                }
                ++p;
            }
            if (!closed)
            {
                pos_ = static_cast<std::size_t>(p - begin);
                line_ = line;
                throw error_at(start_line, "unterminated /* comment (reached end of file)");
            }
        }
        else
            break;
    }
    pos_ = static_cast<std::size_t>(p - begin);
    line_ = line;
}

FoamToken FoamTokenizer::next()
{
    if (has_peek_)
    {
        has_peek_ = false;
        pos_ = peek_pos_;
        line_ = peek_line_;
        return std::move(peek_);
    }
    return scan();
}

const FoamToken& FoamTokenizer::peek()
{
    if (!has_peek_)
    {
        const std::size_t pos = pos_;
        const std::size_t line = line_;
        try
        {
            peek_ = scan();
        }
        catch (...)
        {
            pos_ = pos;
            line_ = line;
            throw;
        }
        peek_pos_ = pos_;
        peek_line_ = line_;
        pos_ = pos;
        line_ = line;
        has_peek_ = true;
    }
    return peek_;
}

bool FoamTokenizer::at_end()
{
    return peek().is_end();
}

FoamToken FoamTokenizer::scan()
{
    skip_whitespace_and_comments();
    FoamToken t;
    t.line = line_;
    t.offset = pos_;
    if (pos_ >= buffer_.size())
    {
        t.type = TokenType::end;
        t.end = pos_;
        return t;
    }
    const char c = buffer_[pos_];
    if (is_punct(c))
    {
        t.type = TokenType::punctuation;
        t.punct = c;
        t.text.assign(1, c);
        ++pos_;
    }
    else if (c == '"')
        scan_string(t);
    else if (c == '#' && pos_ + 1 < buffer_.size() && buffer_[pos_ + 1] == '{')
    {
        // Verbatim block `#{ ... #}` (code in coded entries): one string token.
        const std::size_t close = buffer_.find("#}", pos_ + 2);
        if (close == std::string_view::npos)
            throw error_at(t.line, "unterminated verbatim block '#{' (reached end of file)");
        const std::string_view body = buffer_.substr(pos_ + 2, close - pos_ - 2);
        for (char b : body)
            if (b == '\n')
                ++line_;
        t.type = TokenType::string;
        t.text.assign(body);
        pos_ = close + 2;
    }
    else if (!scan_number(t))
        scan_word(t);
    t.end = pos_;
    return t;
}

bool FoamTokenizer::scan_number(FoamToken& t)
{
    using Kind = number_lexer::NumberToken::Kind;
    const char* const begin = buffer_.data();
    const char* const end = begin + buffer_.size();
    const char* p = begin + pos_;
    if (!starts_number(p, end))
        return false;
    const char* const q = number_lexer::token_end(p, end);
    const number_lexer::NumberToken n = number_lexer::convert_number_token(p, q);
    if (n.kind == Kind::malformed)
        throw error_at(line_, "malformed number '" + std::string(p, q) + "'");
    // Out-of-range integers are read as scalars; overflowing floats are an error,
    // underflow (denormal / zero) is accepted like strtod does.
    if (n.kind == Kind::out_of_range)
        throw error_at(line_, "number out of range '" + std::string(p, q) + "'");
    t.type = n.kind == Kind::label ? TokenType::label : TokenType::scalar;
    t.label = n.label;
    t.scalar = n.scalar;
    t.text.assign(p, q);
    pos_ = static_cast<std::size_t>(q - begin);
    return true;
}

void FoamTokenizer::scan_word(FoamToken& t)
{
    const char* const begin = buffer_.data();
    const char* const end = begin + buffer_.size();
    const char* p = begin + pos_;
    const char* q = p;
    if (*q == '$' && q + 1 < end && q[1] == '{')
    {
        // ${var}: the braces belong to the word, and may nest (`${_${FOAM_EXECUTABLE}}`).
        int depth = 0;
        for (++q; q < end; ++q)
        {
            if (*q == '{')
                ++depth;
            else if (*q == '}' && --depth == 0)
                break;
            else if (*q == '\n')
                break;
        }
        if (q == end || *q != '}')
            throw error_at(line_, "unterminated '${' variable (no closing '}')");
        ++q;
    }
    else
    {
        // As in OpenFOAM, a word may contain balanced parentheses, so `div(phi,U)` and
        // `laplacian((1|A(U)),p)` are single words; `List<vector>` keeps its angle brackets.
        int depth = 0;
        for (; q < end; ++q)
        {
            const char c = *q;
            if (is_space(c) || c == '"' || c == ';' || c == '{' || c == '}')
                break;
            if (c == '/' && q + 1 < end && (q[1] == '/' || q[1] == '*'))
                break;
            if (c == '(')
                ++depth;
            else if (c == ')')
            {
                if (depth == 0)
                    break;
                --depth;
            }
            else if (depth == 0 && (c == '[' || c == ']' || c == ','))
                break;
        }
    }
    t.type = TokenType::word;
    t.text.assign(p, q);
    pos_ = static_cast<std::size_t>(q - begin);
}

void FoamTokenizer::scan_string(FoamToken& t)
{
    const std::size_t start_line = line_;
    std::size_t line = line_;
    std::size_t i = pos_ + 1;
    const std::size_t n = buffer_.size();
    t.type = TokenType::string;
    std::string& out = t.text;
    while (i < n)
    {
        const char c = buffer_[i];
        if (c == '"')
        {
            pos_ = i + 1;
            line_ = line;
            return;
        }
        if (c == '\\' && i + 1 < n)
        {
            const char d = buffer_[i + 1];
            if (d == '"' || d == '\\')
            {
                out.push_back(d);
                i += 2;
                continue;
            }
            if (d == '\n')
            {
                // Line continuation, as in OpenFOAM.
                ++line;
                i += 2;
                continue;
            }
            out.push_back(c);
            ++i;
            continue;
        }
        if (c == '\n')
            ++line;
        out.push_back(c);
        ++i;
    }
    pos_ = n;
    line_ = line;
    throw error_at(start_line, "unterminated string (reached end of file)");
}

std::string_view FoamTokenizer::read_raw(std::size_t n)
{
    discard_peek();
    if (n > buffer_.size() - pos_)
        throw error("unexpected end of file: expected " + std::to_string(n) +
                    " bytes of binary data, only " + std::to_string(buffer_.size() - pos_) +
                    " remain");
    const std::string_view data = buffer_.substr(pos_, n);
    for (const char *p = data.data(), *e = data.data() + n;;)
    {
        const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(e - p));
        if (!nl)
            break;
        ++line_;
        p = static_cast<const char*>(nl) + 1;
    }
    pos_ += n;
    return data;
}

void FoamTokenizer::expect(char c)
{
    if (has_peek_ && peek_.is_punct(c))
    {
        next();
        return;
    }
    skip_blanks();
    if (pos_ < buffer_.size() && buffer_[pos_] == c)
    {
        ++pos_;
        return;
    }
    const FoamToken t = scan();
    throw error_at(t.line, std::string("expected '") + c + "' but found " + t.describe());
}

bool FoamTokenizer::accept(char c)
{
    if (has_peek_)
    {
        if (peek_.is_punct(c))
        {
            next();
            return true;
        }
        return false;
    }
    skip_whitespace_and_comments();
    if (pos_ < buffer_.size() && buffer_[pos_] == c && is_punct(c))
    {
        ++pos_;
        return true;
    }
    return false;
}

std::string FoamTokenizer::expect_word(std::string_view what)
{
    FoamToken t = next();
    if (!t.is_word())
        throw error_at(t.line, "expected " + std::string(what) + " but found " + t.describe());
    return std::move(t.text);
}

std::int64_t FoamTokenizer::expect_label(std::string_view what)
{
    std::int64_t v = 0;
    if (read_label(v))
        return v;
    const FoamToken t = next();
    throw error_at(t.line, "expected " + std::string(what) + " but found " + t.describe());
}

double FoamTokenizer::expect_scalar(std::string_view what)
{
    double v = 0.0;
    if (read_scalar(v))
        return v;
    const FoamToken t = next();
    throw error_at(t.line, "expected " + std::string(what) + " but found " + t.describe());
}

std::int64_t FoamTokenizer::expect_size(std::string_view what)
{
    const std::size_t line = (skip_whitespace_and_comments(), line_);
    const std::int64_t v = expect_label(what);
    if (v < 0)
        throw error_at(line, "expected " + std::string(what) + " but found negative " +
                                 std::to_string(v));
    return v;
}

char FoamTokenizer::peek_char()
{
    if (has_peek_)
        return peek_.is_end() ? '\0' : buffer_[peek_.offset];
    skip_blanks();
    return pos_ < buffer_.size() ? buffer_[pos_] : '\0';
}

bool FoamTokenizer::read_label(std::int64_t& value)
{
    if (has_peek_)
    {
        if (!peek_.is_label())
            return false;
        value = peek_.label;
        next();
        return true;
    }
    skip_blanks();
    const char* const begin = buffer_.data();
    const char* const end = begin + buffer_.size();
    const char* p = begin + pos_;
    if (p == end)
        return false;
    if (!number_lexer::lex_label<Dialect::tokenizer>(p, end, value))
        return false;
    pos_ = static_cast<std::size_t>(p - begin);
    return true;
}

bool FoamTokenizer::read_scalar(double& value)
{
    if (has_peek_)
    {
        if (!peek_.is_number())
            return false;
        value = peek_.scalar;
        next();
        return true;
    }
    skip_blanks();
    const char* const begin = buffer_.data();
    const char* const end = begin + buffer_.size();
    const char* p = begin + pos_;
    if (!starts_number(p, end))
        return false;
    if (number_lexer::lex_scalar<Dialect::tokenizer>(p, end, value))
    {
        pos_ = static_cast<std::size_t>(p - begin);
        return true;
    }
    // Rare paths (underflow, out-of-range, malformed): let the general scanner decide.
    const FoamToken& t = peek();
    if (!t.is_number())
        return false;
    value = t.scalar;
    next();
    return true;
}

void FoamTokenizer::read_vector(double* xyz)
{
    expect('(');
    for (int k = 0; k < 3; ++k)
    {
        if (!read_scalar(xyz[k]))
        {
            const FoamToken t = next();
            throw error_at(t.line, "expected a vector component (x y z) but found " + t.describe());
        }
    }
    skip_blanks();
    if (pos_ < buffer_.size() && buffer_[pos_] == ')')
    {
        ++pos_;
        return;
    }
    const FoamToken t = scan();
    throw error_at(t.line, "expected ')' closing a 3-component vector but found " + t.describe());
}

} // namespace meshmorph::io
