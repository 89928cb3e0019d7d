// SPDX-License-Identifier: GPL-3.0-or-later
//! \file OpenFOAM dictionaries (docs/polymesh-format.md §2): ordered entries, sub-dictionaries,
//! regex keys, merge semantics, `#include`, `$var` substitution, lists (ASCII and binary
//! `List<T>` compounds), and typed, checked getters whose errors name file, line and keyword.
//!
//! Usage:
//! \code
//!   FoamDictionary dict = read_dictionary(case_dir / "system/morphMeshDict");
//!   double tol = dict.get_or<double>("tolerance", 1e-6);
//!   const FoamDictionary& wing = dict.sub_dict("boundary").sub_dict("wing");
//!   Vector3 v = wing.get<Vector3>("vector");   // ParseError "…/morphMeshDict:12: keyword
//!                                              // 'vector' is undefined in dictionary
//!                                              'boundary.wing'"
//! \endcode
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <regex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/types.h"
#include "meshmorph/io/foam_header.h"
#include "meshmorph/io/foam_tokenizer.h"

namespace meshmorph::io
{

//! A decoded `List<T>` compound token (`List<label> 8(0 1 …)`, ASCII or binary), stored
//! compactly instead of as millions of tokens.
struct FoamCompound
{
    enum class Kind
    {
        label,   //!< List<label>: `labels`
        scalar,  //!< List<scalar>: `scalars`
        vector,  //!< List<vector>: `scalars`, 3 per element (x y z)
        boolean, //!< List<bool>: `labels` (0/1)
        word,    //!< List<word>: `words`
    };
    Kind kind = Kind::label;
    std::string type_word;            //!< as written, e.g. "List<label>"
    std::vector<std::int64_t> labels; //!< label and bool elements
    std::vector<double> scalars;      //!< scalar elements, or vector components
    std::vector<std::string> words;   //!< word elements

    //! Number of elements (vectors count once).
    std::size_t size() const;
};

//! One token of an entry's value: a FoamToken, or a decoded compound list
//! (type == TokenType::word with `text` = "List<…>" and `compound` set).
struct FoamValueToken : FoamToken
{
    std::shared_ptr<const FoamCompound> compound; //!< set for `List<T>` compounds
    bool is_compound() const { return compound != nullptr; }
};

class FoamDictionary;

//! Options for parsing a dictionary.
struct ParseOptions
{
    //! Binary list bodies (`List<label>` followed by `\nN\n(` raw bytes `)`). Set
    //! automatically from the `FoamFile` header when the text has one.
    bool binary = false;
    int label_bytes = 4;  //!< binary label size (4 or 8)
    int scalar_bytes = 8; //!< binary scalar size (4 or 8)
    //! Case directory for `<case>/`, `<system>/`, `<constant>/` in #include. Empty: derived
    //! from the file path (the parent of its `system`/`constant` directory, else its directory).
    std::filesystem::path case_dir;
    //! Reads an included file (decompressed contents), or returns nullopt when it does not
    //! exist. Empty: read from disk, plain or `.gz`.
    std::function<std::optional<std::string>(const std::filesystem::path&)> read_file;
    //! Maximum #include nesting (guards against include cycles).
    int max_include_depth = 32;
    //! For dictionaries of which a tool reads a few entries (controlDict): `#includeFunc`,
    //! `#includeModel` and `#includeEtc` are skipped, and a `#calc`, `#codeStream` or
    //! `#eval` value is kept as its directive word, so that reading that entry is an error
    //! naming it while every other entry reads normally. Default: all of them are errors.
    bool skip_unsupported = false;
};

//! One entry: keyword and either a sub-dictionary or a value (token stream).
class FoamEntry
{
public:
    FoamEntry() = default;
    FoamEntry(const FoamEntry& other);
    FoamEntry& operator=(const FoamEntry& other);
    FoamEntry(FoamEntry&&) noexcept = default;
    FoamEntry& operator=(FoamEntry&&) noexcept = default;
    ~FoamEntry();

    //! The keyword as written (without quotes for a regex key).
    const std::string& keyword() const { return keyword_; }
    //! Whether the keyword was quoted (a regular expression, ECMAScript, whole-match).
    bool is_regex() const { return regex_ != nullptr; }
    //! Whether `name` matches this entry's keyword (exactly, or as a whole-match regex).
    bool matches(const std::string& name) const;
    bool is_dict() const { return dict_ != nullptr; }
    //! \pre is_dict()
    const FoamDictionary& dict() const { return *dict_; }
    FoamDictionary& dict() { return *dict_; }
    //! The value tokens (empty for a sub-dictionary or `key;`), after `$var` substitution.
    const std::vector<FoamValueToken>& tokens() const { return tokens_; }
    //! \brief The exact characters of the value between the keyword and the `;` (trimmed of
    //! surrounding whitespace), or of the sub-dictionary including its braces, e.g.
    //! "1(wall)" for `inGroups 1(wall);`. For a value built by `$var` substitution, the
    //! source text of the `$var` itself.
    const std::string& source_text() const { return source_; }
    //! File the entry was read from (the included file for #include'd entries).
    const std::string& path() const { return path_; }
    //! 1-based line of the keyword.
    std::size_t line() const { return line_; }
    //! Dotted scope of the entry's dictionary ("" for the top level, "boundary.wing").
    const std::string& scope() const { return scope_; }

    //! \brief The value converted to T, starting at token `first`. Supported T as for
    //! FoamDictionary::get. \throw ParseError "path:line: keyword 'k' ...: expected ..."
    //! if the tokens do not form exactly one T (trailing tokens are an error).
    template <class T> T get(std::size_t first = 0) const;

    //! ParseError at this entry: "path:line: keyword 'k' in dictionary 's': msg".
    ParseError error(const std::string& msg) const;

private:
    friend class FoamDictionary;
    friend struct detail_dictionary_access;
    std::string keyword_;
    std::shared_ptr<const std::regex> regex_;
    std::unique_ptr<FoamDictionary> dict_;
    std::vector<FoamValueToken> tokens_;
    std::string source_;
    std::string path_;
    std::size_t line_ = 0;
    std::string scope_;
};

//! An ordered OpenFOAM dictionary. Value type (copyable, movable).
class FoamDictionary
{
public:
    FoamDictionary() = default;
    //! Path used in messages, dotted scope name ("" = top level), line of the opening `{`.
    FoamDictionary(std::string path, std::string scope, std::size_t line = 0);

    //! File the dictionary was read from (for messages).
    const std::string& path() const { return path_; }
    //! Dotted scope name: "" for the top level, "boundary.wing" for a nested dictionary.
    const std::string& scope() const { return scope_; }
    //! Scope for messages: scope(), or the file name's last component for the top level.
    std::string scope_name() const;
    //! Line of the opening `{` (for the top level: the first line of the file, 1).
    std::size_t line() const { return line_; }
    //! Line of the closing `}` (for the top level: the last line of the file).
    std::size_t end_line() const { return end_line_; }
    //! The `FoamFile` header, when the text had one.
    const std::optional<FoamHeader>& header() const { return header_; }
    void set_header(FoamHeader header) { header_ = std::move(header); }

    //! \brief The entry for `key`: exact keyword first, then regex keywords, the one written
    //! last first. nullptr when none matches.
    const FoamEntry* find(const std::string& key) const;
    FoamEntry* find(const std::string& key);
    //! \brief Like find(). \throw ParseError "path:line: keyword 'k' is undefined in
    //! dictionary 's'" (line: the dictionary's `{`, or 1 for the top level).
    const FoamEntry& entry(const std::string& key) const;
    bool found(const std::string& key) const { return find(key) != nullptr; }
    //! Whether `key` exists and is a sub-dictionary.
    bool is_dict(const std::string& key) const;
    //! \throw ParseError if undefined or not a sub-dictionary.
    const FoamDictionary& sub_dict(const std::string& key) const;
    //! The sub-dictionary for `key` or nullptr.
    const FoamDictionary* find_dict(const std::string& key) const;
    //! Keywords in file order (regex keywords without quotes).
    std::vector<std::string> keys() const;
    //! All entries in file order.
    const std::vector<FoamEntry>& entries() const { return entries_; }
    std::size_t size() const { return entries_.size(); }
    bool empty() const { return entries_.empty(); }
    //! Line of the entry for `key`. \throw ParseError if undefined.
    std::size_t entry_line(const std::string& key) const { return entry(key).line(); }

    //! \brief The value of `key` as T. Supported T: double, float, std::int64_t, std::int32_t
    //! (range-checked; also Index), bool (yes/no/on/off/true/false/y/n/none), std::string (a
    //! word or a string), Vector3 (`(x y z)`), std::vector<double>, std::vector<std::int64_t>,
    //! std::vector<std::int32_t>, std::vector<std::string>, std::vector<Vector3>. Lists may
    //! be written `N(…)`, `(…)`, `N{v}` or as a `List<T>` compound.
    //! \throw ParseError naming file, line and keyword when undefined, a sub-dictionary, or
    //! not convertible.
    template <class T> T get(const std::string& key) const { return entry(key).get<T>(); }
    //! \brief The value of `key` as T, or `fallback` when undefined (a present but invalid
    //! value still throws).
    template <class T> T get_or(const std::string& key, const T& fallback) const
    {
        const FoamEntry* e = find(key);
        return e ? e->get<T>() : fallback;
    }
    //! get_or for a string literal fallback: `dict.get_or("method", "rbf")`.
    std::string get_or(const std::string& key, const char* fallback) const
    {
        return get_or<std::string>(key, std::string(fallback));
    }

    //! \brief Add or merge an entry with the given input mode semantics (`merge`: a later
    //! entry replaces an earlier one; two sub-dictionaries merge recursively).
    void add(FoamEntry entry, bool merge = true);
    //! Remove the entry with exactly this keyword (regex keys: the written pattern). Returns
    //! whether one was removed.
    bool remove(const std::string& keyword);
    //! \brief Reject keywords not in `allowed` (a typo must not be silently ignored), except
    //! those in `helpers` (not listed as valid).
    //! \throw ParseError at the offending entry: "path:line: unknown keyword for <what>
    //! (valid: a b c)".
    void check_keywords(const std::vector<std::string>& allowed, const std::string& what,
                        const std::vector<std::string>& helpers = {}) const;
    //! \brief The top-level keywords that some entry's text refers to as a variable
    //! (`$name`, `${name}`, `$name.sub`, `${/name}`, `$:name`): helper entries, the
    //! OpenFOAM idiom for parameter studies (`lift 0.05; ... vector (0 0 $lift);`).
    std::vector<std::string> referenced_variables() const;

    //! ParseError at this dictionary: "path:line: msg".
    ParseError error(const std::string& msg) const;

private:
    friend struct detail_dictionary_access;
    std::string path_;
    std::string scope_;
    std::size_t line_ = 0;
    std::size_t end_line_ = 0;
    std::optional<FoamHeader> header_;
    std::vector<FoamEntry> entries_;
};

// Supported instantiations of FoamEntry::get (defined in foam_dictionary.cpp).
template <> double FoamEntry::get<double>(std::size_t) const;
template <> float FoamEntry::get<float>(std::size_t) const;
template <> std::int64_t FoamEntry::get<std::int64_t>(std::size_t) const;
template <> std::int32_t FoamEntry::get<std::int32_t>(std::size_t) const;
template <> bool FoamEntry::get<bool>(std::size_t) const;
template <> std::string FoamEntry::get<std::string>(std::size_t) const;
template <> Vector3 FoamEntry::get<Vector3>(std::size_t) const;
template <> std::vector<double> FoamEntry::get<std::vector<double>>(std::size_t) const;
template <> std::vector<std::int64_t> FoamEntry::get<std::vector<std::int64_t>>(std::size_t) const;
template <> std::vector<std::int32_t> FoamEntry::get<std::vector<std::int32_t>>(std::size_t) const;
template <> std::vector<std::string> FoamEntry::get<std::vector<std::string>>(std::size_t) const;
template <> std::vector<Vector3> FoamEntry::get<std::vector<Vector3>>(std::size_t) const;

//! \brief Parse dictionary text (a whole file). A leading `FoamFile` header is parsed with
//! parse_header(), sets binary/label/scalar sizes, and is available as header().
//! \param path used for messages and as the base of relative #include paths.
//! \throw ParseError "path:line: ..." on malformed input, a missing #include file,
//! `#includeEtc`, `#calc`, `#codeStream`, `#eval`, an undefined `$var`.
FoamDictionary parse_dictionary(std::string_view text, const std::string& path,
                                const ParseOptions& options = {});

//! \brief Parse the remaining entries of `tokenizer` up to the end of input (after the
//! caller has read the header with parse_header). Use the header's format in `options`.
FoamDictionary parse_dictionary_body(FoamTokenizer& tokenizer, const ParseOptions& options = {});

//! \brief Parse one `{ … }` block (the next token must be `{`), consuming the `}`.
//! \param scope dotted scope name for messages ("boundary.wing").
FoamDictionary parse_dictionary_block(FoamTokenizer& tokenizer, const std::string& scope,
                                      const ParseOptions& options = {});

//! \brief Read and parse a dictionary file, `path` or else `path.gz`.
//! \throw IoError if neither exists or cannot be read; ParseError as parse_dictionary.
FoamDictionary read_dictionary(const std::filesystem::path& path, ParseOptions options = {});

//! \brief Read a `List<T>` compound body after its type word (`N(…)`, `N{v}`, `(…)`, or a
//! binary block when options.binary and T is contiguous) with foam_lists.h's readers.
//! \param type_word "List<label>", "List<scalar>", "List<vector>", "List<bool>", "List<word>".
//! \param what names the list in messages (the entry's keyword); empty: the type word.
//! \throw ParseError naming file and line on an unknown type word, a size mismatch,
//! a bad element or truncated data.
FoamCompound read_compound(FoamTokenizer& tokenizer, const std::string& type_word,
                           const ParseOptions& options = {}, const std::string& what = {});

//! A uniform list `N{v}` is expanded in memory but is a few bytes of text for any N, so N
//! cannot be checked against the input left. OpenFOAM writes a field of equal values as
//! `uniform v`, so a dictionary's N{v} is short; this bound (polyMesh lists use the same,
//! ListReadOptions::max_uniform_size) keeps a hostile `2000000000{(0 0 0)}` from asking for
//! 48 GB.
inline constexpr std::int64_t max_uniform_list_size = std::int64_t(1) << 24;

//! \brief How quoted (regex) keywords are compiled, here and wherever they are matched again:
//! ECMAScript, and with libstdc++ its polynomial-time matcher, so that a keyword such as
//! `"(a*)*b"` cannot take exponential time on a long name. That matcher refuses
//! back-references, which OpenFOAM's (POSIX) keyword regexes do not have either.
inline constexpr std::regex::flag_type keyword_regex_flags = std::regex::ECMAScript
#ifdef __GLIBCXX__
                                                             | std::regex_constants::__polynomial
#endif
    ;

//! Whether `word` names a compound type read_compound() understands (`List<label>`, …).
bool is_compound_type(std::string_view word);

} // namespace meshmorph::io
