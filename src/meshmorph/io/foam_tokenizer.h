// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Tokenizer for OpenFOAM's text syntax (docs/polymesh-format.md §2), with line counting
//! and fast in-place number readers for large lists.
//!
//! The tokenizer reads a buffer the caller owns (a whole file, already decompressed) and
//! never copies it. Tokens are punctuation `( ) { } [ ] ;` (and `,`), words (`patch`,
//! `List<vector>`, `#include`, `$var`), strings (`"..."` with `\"` and `\\` escapes), labels
//! (int64) and scalars (double). A count glued to a bracket (`4(1 2 3 4)`, `6{0}`) is two
//! tokens. As in OpenFOAM, a word may contain balanced parentheses once started
//! (`div(phi,U)`, `laplacian((1|A(U)),p)`), so write a space between a word and a list.
//! Comments `//` and `/* */` are skipped everywhere.
//!
//! Binary list blocks are read by byte count with read_raw() right after the `(` token has
//! been consumed with expect('('). Never call peek() inside a binary block: it would scan
//! the raw bytes as text.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "meshmorph/core/exceptions.h"

namespace meshmorph::io
{

//! Kind of a FoamToken.
enum class TokenType
{
    end,         //!< end of input (no more tokens)
    punctuation, //!< one of ( ) { } [ ] ; ,
    word,        //!< a word: keyword, `List<label>`, `#include`, `$var`, `nonuniform`, `on`, ...
    string,      //!< a quoted string; `text` holds the unescaped contents
    label,       //!< an integer (int64)
    scalar,      //!< a floating-point number (also `nan`, `inf` are words, not scalars)
};

//! One token. `text` is the word, the unescaped string, or the punctuation character.
struct FoamToken
{
    TokenType type = TokenType::end;
    char punct = 0;         //!< for punctuation
    std::string text;       //!< word / unescaped string / number spelling / punctuation
    std::int64_t label = 0; //!< for label
    double scalar = 0.0;    //!< for scalar and label (label converted)
    std::size_t line = 0;   //!< 1-based line where the token starts
    std::size_t offset = 0; //!< byte offset of the first character in the buffer
    std::size_t end = 0;    //!< byte offset one past the last character

    bool is_end() const { return type == TokenType::end; }
    bool is_punct(char c) const { return type == TokenType::punctuation && punct == c; }
    bool is_word() const { return type == TokenType::word; }
    bool is_word(std::string_view w) const { return type == TokenType::word && text == w; }
    bool is_string() const { return type == TokenType::string; }
    bool is_label() const { return type == TokenType::label; }
    //! A label or a scalar (a number is acceptable where a scalar is expected).
    bool is_number() const { return type == TokenType::label || type == TokenType::scalar; }
    //! Human-readable description for messages: `'('`, `word 'patch'`, `label 4`, `end of file`.
    std::string describe() const;
};

//! Tokenizer over a caller-owned buffer. Not thread-safe; cheap to construct.
class FoamTokenizer
{
public:
    //! \param buffer the whole text (must outlive the tokenizer).
    //! \param path used in error messages ("path:line: message").
    //! \param first_line line number of buffer[0] (1 for a whole file).
    FoamTokenizer(std::string_view buffer, std::string path, std::size_t first_line = 1);

    //! \brief The next token (TokenType::end at end of input).
    //! \throw ParseError on an unterminated string or comment (line where it started), or a
    //! malformed number such as `1.2.3`.
    FoamToken next();
    //! The next token without consuming it (line()/offset() are unchanged). The reference
    //! stays valid until the tokenizer is used again.
    const FoamToken& peek();
    //! Whether only whitespace and comments remain.
    bool at_end();

    //! Current 1-based line of the read position.
    std::size_t line() const { return line_; }
    //! Current byte offset of the read position.
    std::size_t offset() const { return pos_; }
    const std::string& path() const { return path_; }
    std::string_view buffer() const { return buffer_; }
    //! buffer()[begin, end) (clamped to the buffer).
    std::string_view slice(std::size_t begin, std::size_t end) const;

    //! Skip spaces, newlines and comments. \throw ParseError on an unterminated `/*`.
    void skip_whitespace_and_comments();

    //! \brief The next n raw bytes (binary list data), advancing past them and counting the
    //! newlines they contain. Discards a pending peek.
    //! \throw ParseError "unexpected end of file ... expected n bytes" if fewer remain.
    std::string_view read_raw(std::size_t n);

    //! \brief Consume punctuation `c`. \throw ParseError "expected '(' but found ..." otherwise.
    void expect(char c);
    //! \brief Consume a word and return it. \param what describes the expectation for errors.
    std::string expect_word(std::string_view what = "a word");
    //! \brief Consume a label. \throw ParseError if the next token is not an integer.
    std::int64_t expect_label(std::string_view what = "an integer");
    //! \brief Consume a number (label or scalar) as double.
    double expect_scalar(std::string_view what = "a number");
    //! \brief Consume a non-negative label (list sizes). \throw ParseError if negative.
    std::int64_t expect_size(std::string_view what = "a list size");
    //! Consume punctuation `c` if it is next; returns whether it did.
    bool accept(char c);
    //! \brief Skip whitespace/comments and return the next raw character without consuming
    //! it ('\0' at end of input). Cheap look-ahead for list loops (no token is built).
    char peek_char();

    //! \brief Hot-loop reader: skip whitespace/comments and parse an integer in place.
    //! Returns false (consuming nothing but whitespace/comments) if the next token is not an
    //! integer (e.g. `(`, `)`, a word or a scalar like `1.5`).
    bool read_label(std::int64_t& value);
    //! \brief Hot-loop reader: like read_label but for a number (integer or float) as double.
    bool read_scalar(double& value);
    //! \brief Hot-loop reader for `( x y z )`. \throw ParseError if not exactly that.
    void read_vector(double* xyz);

    //! \brief ParseError "path:line: msg" at the current line.
    ParseError error(const std::string& msg) const;
    //! \brief ParseError "path:line: msg" at a given line.
    ParseError error_at(std::size_t line, const std::string& msg) const;

private:
    // Inline fast path of skip_whitespace_and_comments for the hot readers.
    void skip_blanks()
    {
        if (has_peek_)
            has_peek_ = false;
        const std::size_t n = buffer_.size();
        while (pos_ < n)
        {
            const char c = buffer_[pos_];
            if (c == '\n')
                ++line_;
            else if (c != ' ' && c != '\t' && c != '\r')
            {
                if (c == '/' || c == '\f' || c == '\v')
                    skip_whitespace_and_comments();
                return;
            }
            ++pos_;
        }
    }
    FoamToken scan();
    void scan_word(FoamToken& t);
    void scan_string(FoamToken& t);
    bool scan_number(FoamToken& t);
    void discard_peek();

    std::string_view buffer_;
    std::string path_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    bool has_peek_ = false;
    FoamToken peek_;
    std::size_t peek_pos_ = 0;
    std::size_t peek_line_ = 1;
};

} // namespace meshmorph::io
