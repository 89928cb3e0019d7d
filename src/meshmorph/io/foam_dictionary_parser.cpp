// SPDX-License-Identifier: GPL-3.0-or-later
// The OpenFOAM dictionary parser: entries, directives (#include, #inputMode, #remove, ...),
// $variable substitution with scoping, and the parse/read entry points.
#include "meshmorph/io/foam_dictionary.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <limits>
#include <optional>

#include "meshmorph/core/log.h"
#include "meshmorph/io/foam_file.h"

namespace fs = std::filesystem;

namespace meshmorph::io
{

namespace
{

// Reads `path`, or `path.gz` when only that exists (io/foam_file.h rules: gzip detected by
// its magic bytes, a warning when both exist); nullopt when neither exists.
std::optional<std::string> read_file_plain_or_gz(const fs::path& path)
{
    if (!foam_file_exists(path)) // no lookup warning here: read_foam_file gives it once
        return std::nullopt;
    return read_foam_file(path).data;
}

bool is_number_name(const std::string& s)
{
    if (s.empty())
        return false;
    char* end = nullptr;
    std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size();
}

// The case directory of a file: parent of its system/, constant/, <time>/ directory.
fs::path derive_case_dir(const fs::path& file)
{
    fs::path dir = file.parent_path();
    const std::string name = dir.filename().string();
    if (name == "polyMesh")
        return dir.parent_path().parent_path();
    if (name == "system" || name == "constant" || is_number_name(name))
        return dir.parent_path();
    return dir;
}

std::string child_scope(const std::string& scope, const std::string& key)
{
    return scope.empty() ? key : scope + "." + key;
}

bool is_code_directive(const std::string& w)
{
    return w == "#calc" || w == "#codeStream" || w == "#eval";
}

[[noreturn]] void throw_code_directive(const FoamTokenizer& tok, std::size_t line,
                                       const std::string& w)
{
    throw tok.error_at(line, "'" + w +
                                 "' is not supported: it needs a C++ compiler or an expression "
                                 "engine; write the value out instead");
}

// Limits that keep hostile input from overflowing the stack: sub-dictionaries are parsed
// (and destroyed) recursively, and std::regex compiles recursively, about one level per
// character. Real dictionaries nest a few levels and their regex keys are short.
constexpr std::size_t max_dictionary_nesting = 128;
constexpr std::size_t max_regex_keyword_size = 1024;
// std::regex copies an atom once per repetition ({n,m}: up to max(n, m) copies, nested
// repetitions multiply), and overflows a `long` on a count of 19 digits (undefined
// behaviour inside libstdc++); keywords in OpenFOAM cases use no counts at all.
constexpr std::uint64_t max_regex_repetitions = 10000;

// The number at pattern[i...] (i moved past its digits), saturated above
// max_regex_repetitions; nullopt when no digit is there.
std::optional<std::uint64_t> read_count(const std::string& pattern, std::size_t& i)
{
    std::optional<std::uint64_t> count;
    for (; i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i])); ++i)
        count = std::min<std::uint64_t>(count.value_or(0) * 10 + std::uint64_t(pattern[i] - '0'),
                                        max_regex_repetitions + 1);
    return count;
}

// The product over the {n}, {n,}, {n,m} of `pattern` of (copies + 1), copies being the larger
// of n and m; saturated above max_regex_repetitions. Escaped braces and braces in
// [...] are literal.
std::uint64_t regex_repetitions(const std::string& pattern)
{
    std::uint64_t product = 1;
    bool in_class = false;
    for (std::size_t i = 0; i < pattern.size(); ++i)
    {
        const char c = pattern[i];
        if (c == '\\')
            ++i;
        else if (in_class)
            in_class = c != ']';
        else if (c == '[')
            in_class = true;
        else if (c == '{')
        {
            ++i;
            std::optional<std::uint64_t> copies = read_count(pattern, i);
            if (i < pattern.size() && pattern[i] == ',')
            {
                ++i;
                if (const std::optional<std::uint64_t> m = read_count(pattern, i))
                    copies = std::max(copies.value_or(0), *m); // n > m is an error, after n is read
            }
            product = std::min(product * (copies.value_or(0) + 1), max_regex_repetitions + 1);
            --i; // the loop's ++i moves to the character after the counts
        }
    }
    return product;
}

// The longest run of digits right after a backslash (a back-reference `\12`): std::regex
// reads it into a `long` that 19 digits overflow.
std::size_t longest_escaped_number(const std::string& pattern)
{
    std::size_t longest = 0;
    for (std::size_t i = 0; i + 1 < pattern.size(); ++i)
        if (pattern[i] == '\\')
        {
            std::size_t digits = 0;
            while (i + 1 + digits < pattern.size() &&
                   std::isdigit(static_cast<unsigned char>(pattern[i + 1 + digits])))
                ++digits;
            longest = std::max(longest, digits);
            i += std::max<std::size_t>(digits, 1); // past the escaped character
        }
    return longest;
}

// A quoted keyword compiled as a regular expression; `what` names its use in messages.
std::regex compile_keyword_regex(const FoamTokenizer& tok, const FoamToken& key,
                                 const std::string& what)
{
    if (key.text.size() > max_regex_keyword_size)
        throw tok.error_at(key.line, what + " of " + std::to_string(key.text.size()) +
                                         " characters is longer than the " +
                                         std::to_string(max_regex_keyword_size) + " supported");
    if (regex_repetitions(key.text) > max_regex_repetitions)
        throw tok.error_at(key.line, what + " \"" + key.text + "\" repeats more than " +
                                         std::to_string(max_regex_repetitions) +
                                         " times in all (its {n,m} counts multiplied)");
    if (longest_escaped_number(key.text) > 4)
        throw tok.error_at(key.line, what + " \"" + key.text +
                                         "\" has a back-reference number of more than 4 digits");
    try
    {
        return std::regex(key.text, keyword_regex_flags);
    }
    catch (const std::regex_error& ex)
    {
        throw tok.error_at(key.line, "invalid " + what + " \"" + key.text + "\": " + ex.what());
    }
}

} // namespace

namespace
{

void rescope(FoamDictionary& dict, const std::string& scope);

} // namespace

//! Parser state and private access to FoamDictionary / FoamEntry internals.
struct detail_dictionary_access
{
    enum class InputMode
    {
        merge,
        overwrite,
        protect,
        warn,
        error
    };

    ParseOptions options;
    fs::path case_dir;
    std::vector<FoamDictionary*> scopes;
    InputMode mode = InputMode::merge;
    int include_depth = 0;
    std::deque<FoamEntry> env_entries; // owners of entries made from environment variables

    static void set_scope(FoamDictionary& d, const std::string& s) { d.scope_ = s; }
    static std::vector<FoamEntry>& entries(FoamDictionary& d) { return d.entries_; }
    static void set_entry_scope(FoamEntry& e, const std::string& s) { e.scope_ = s; }
    static void set_lines(FoamDictionary& d, std::size_t begin, std::size_t end)
    {
        d.line_ = begin;
        d.end_line_ = end;
    }
    static void set_end_line(FoamDictionary& d, std::size_t end) { d.end_line_ = end; }

    // Adds `e` to `dict` under the given input mode (docs/polymesh-format.md §2).
    static void insert(FoamDictionary& dict, FoamEntry&& e, InputMode mode)
    {
        FoamEntry* existing = nullptr;
        for (FoamEntry& old : dict.entries_)
            if (old.keyword_ == e.keyword_ && old.is_regex() == e.is_regex())
            {
                existing = &old;
                break;
            }
        if (!existing)
        {
            dict.entries_.push_back(std::move(e));
            return;
        }
        switch (mode)
        {
        case InputMode::merge:
            if (existing->is_dict() && e.is_dict())
            {
                for (FoamEntry& sub : e.dict_->entries_)
                    insert(*existing->dict_, std::move(sub), InputMode::merge);
                return;
            }
            *existing = std::move(e);
            return;
        case InputMode::overwrite:
            *existing = std::move(e);
            return;
        case InputMode::protect:
            return;
        case InputMode::warn:
            log::warning() << e.path_ << ":" << e.line_ << ": duplicate keyword '" << e.keyword_
                           << "' in dictionary '" << dict.scope_name()
                           << "' ignored (#inputMode warn; first defined at line "
                           << existing->line_ << ")";
            return;
        case InputMode::error:
            throw ParseError(e.path_, e.line_,
                             "duplicate keyword '" + e.keyword_ + "' in dictionary '" +
                                 dict.scope_name() + "' (#inputMode error; first defined at " +
                                 existing->path_ + ":" + std::to_string(existing->line_) + ")");
        }
    }

    // ---- scoped lookup for $var -------------------------------------------------------

    // `name` in dict, where `name` may continue into sub-dictionaries with '.' or '/' (a
    // keyword containing dots, such as `motorBike.obj`, is tried whole first).
    static const FoamEntry* find_path(const FoamDictionary& dict, const std::string& name)
    {
        if (const FoamEntry* e = dict.find(name))
            return e;
        for (std::size_t dot = name.find_first_of("./"); dot != std::string::npos;
             dot = name.find_first_of("./", dot + 1))
        {
            const FoamEntry* head = dict.find(name.substr(0, dot));
            if (head && head->is_dict())
                if (const FoamEntry* e = find_path(head->dict(), name.substr(dot + 1)))
                    return e;
        }
        return nullptr;
    }

    const FoamEntry* lookup(std::string name) const
    {
        if (scopes.empty() || name.empty())
            return nullptr;
        // Scopes: `:a.b` (old syntax) and `/a/b` from the top level, `..a` and `../a` from
        // the parent, as OpenFOAM v1912 reads them (`${/endTime}` in stock controlDicts).
        if (name[0] == ':' || name[0] == '/')
            return find_path(*scopes.front(), name.substr(1));
        if (name.rfind("../", 0) == 0)
        {
            std::size_t ups = 0;
            while (name.rfind("../", 0) == 0)
            {
                ++ups;
                name = name.substr(3);
            }
            if (ups >= scopes.size())
                return nullptr;
            return find_path(*scopes[scopes.size() - 1 - ups], name);
        }
        if (name[0] == '.')
        {
            std::size_t dots = 0;
            while (dots < name.size() && name[dots] == '.')
                ++dots;
            if (dots - 1 >= scopes.size())
                return nullptr;
            const FoamDictionary& d = *scopes[scopes.size() - dots];
            return find_path(d, name.substr(dots));
        }
        for (std::size_t level = scopes.size(); level-- > 0;)
            if (const FoamEntry* e = find_path(*scopes[level], name))
                return e;
        return nullptr;
    }

    // Expands inner `${x}` references in a variable name (`_${FOAM_EXECUTABLE}`) from
    // single-token entries or the environment; nullopt when one is undefined.
    std::optional<std::string> expand_inner(std::string name) const
    {
        for (std::size_t at = name.find("${"); at != std::string::npos; at = name.find("${"))
        {
            int depth = 0;
            std::size_t close = at + 1;
            for (; close < name.size(); ++close)
            {
                if (name[close] == '{')
                    ++depth;
                else if (name[close] == '}' && --depth == 0)
                    break;
            }
            if (close >= name.size())
                return std::nullopt;
            const std::optional<std::string> inner =
                expand_inner(name.substr(at + 2, close - at - 2));
            if (!inner)
                return std::nullopt;
            std::string value;
            const FoamEntry* e = lookup(*inner);
            if (e && !e->is_dict() && e->tokens_.size() == 1)
                value = e->tokens_[0].text;
            else if (const char* env = std::getenv(inner->c_str()))
                value = env;
            else
                return std::nullopt;
            name = name.substr(0, at) + value + name.substr(close + 1);
        }
        return name;
    }

    // The entry a `$name` / `${name}` token refers to, or nullptr when undefined.
    const FoamEntry* try_resolve(const FoamTokenizer& tok, const FoamToken& var)
    {
        std::string name = var.text.substr(1);
        if (name.size() >= 2 && name.front() == '{' && name.back() == '}')
            name = name.substr(1, name.size() - 2);
        if (name.empty())
            throw tok.error_at(var.line, "empty variable name '" + var.text + "'");
        const std::optional<std::string> expanded = expand_inner(name);
        if (!expanded)
            return nullptr;
        name = *expanded;
        if (const FoamEntry* e = lookup(name))
            return e;
        // Like OpenFOAM, fall back to an environment variable of that name.
        if (const char* env = std::getenv(name.c_str()))
        {
            FoamEntry e;
            e.keyword_ = name;
            e.source_ = env;
            e.path_ = tok.path();
            e.line_ = var.line;
            FoamTokenizer sub(e.source_, tok.path(), var.line);
            for (FoamToken t = sub.next(); !t.is_end(); t = sub.next())
            {
                FoamValueToken vt;
                static_cast<FoamToken&>(vt) = std::move(t);
                vt.line = var.line;
                e.tokens_.push_back(std::move(vt));
            }
            env_entries.push_back(std::move(e));
            return &env_entries.back();
        }
        return nullptr;
    }

    const FoamEntry& resolve(const FoamTokenizer& tok, const FoamToken& var)
    {
        if (const FoamEntry* e = try_resolve(tok, var))
            return *e;
        throw tok.error_at(var.line, "undefined variable '" + var.text +
                                         "' (no such entry in scope, nor environment variable)");
    }

    // A dictionary's entries as value tokens (how OpenFOAM expands `$dict` inside a list).
    static void dict_tokens(const FoamDictionary& d, std::size_t line,
                            std::vector<FoamValueToken>& out)
    {
        const auto punct = [&](char c)
        {
            FoamValueToken t;
            t.type = TokenType::punctuation;
            t.punct = c;
            t.text.assign(1, c);
            t.line = line;
            out.push_back(std::move(t));
        };
        for (const FoamEntry& e : d.entries_)
        {
            FoamValueToken k;
            k.type = e.is_regex() ? TokenType::string : TokenType::word;
            k.text = e.keyword_;
            k.line = line;
            out.push_back(std::move(k));
            if (e.is_dict())
            {
                punct('{');
                dict_tokens(*e.dict_, line, out);
                punct('}');
            }
            else
            {
                out.insert(out.end(), e.tokens_.begin(), e.tokens_.end());
                punct(';');
            }
        }
    }

    // ---- #include ---------------------------------------------------------------------

    fs::path expand_include(const FoamTokenizer& tok, std::size_t line, std::string s) const
    {
        const auto replace_prefix = [&](const std::string& prefix, const fs::path& base)
        {
            if (s.rfind(prefix, 0) == 0)
            {
                s = (base / s.substr(prefix.size())).string();
                return true;
            }
            return false;
        };
        if (!replace_prefix("<case>/", case_dir) &&
            !replace_prefix("<system>/", case_dir / "system"))
            replace_prefix("<constant>/", case_dir / "constant");
        if (s.rfind("~/", 0) == 0)
            if (const char* home = std::getenv("HOME"))
                s = std::string(home) + s.substr(1);
        std::string out;
        for (std::size_t i = 0; i < s.size();)
        {
            if (s[i] != '$')
            {
                out += s[i++];
                continue;
            }
            std::size_t j = i + 1;
            std::string var;
            if (j < s.size() && s[j] == '{')
            {
                const std::size_t close = s.find('}', j);
                if (close == std::string::npos)
                    throw tok.error_at(line, "unterminated '${' in include path '" + s + "'");
                var = s.substr(j + 1, close - j - 1);
                j = close + 1;
            }
            else
            {
                while (j < s.size() &&
                       (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '_'))
                    ++j;
                var = s.substr(i + 1, j - i - 1);
            }
            const char* value = std::getenv(var.c_str());
            if (value)
                out += value;
            else if (var == "FOAM_CASE")
                out += case_dir.string();
            else
                throw tok.error_at(line, "undefined environment variable '$" + var +
                                             "' in include path '" + s + "'");
            i = j;
        }
        fs::path p(out);
        if (p.is_relative())
            p = fs::path(tok.path()).parent_path() / p;
        return p;
    }

    void include(FoamTokenizer& tok, FoamDictionary& dict, const FoamToken& directive)
    {
        const FoamToken arg = tok.next();
        if (!arg.is_string() && !arg.is_word())
            throw tok.error_at(directive.line, "expected a file name after '" + directive.text +
                                                   "' but found " + arg.describe());
        const bool optional = directive.text != "#include";
        const fs::path file = expand_include(tok, directive.line, arg.text);
        if (include_depth >= options.max_include_depth)
            throw tok.error_at(directive.line, "#include nesting deeper than " +
                                                   std::to_string(options.max_include_depth) +
                                                   " (include cycle?) at '" + file.string() + "'");
        std::optional<std::string> text =
            options.read_file ? options.read_file(file) : read_file_plain_or_gz(file);
        if (!text)
        {
            if (optional)
                return;
            throw tok.error_at(directive.line, "cannot find include file '" + file.string() +
                                                   "' (" + directive.text + " \"" + arg.text +
                                                   "\")");
        }
        FoamTokenizer sub(*text, file.string());
        if (has_header(sub))
            parse_header(sub, false); // an included file's own header is not an entry
        const InputMode saved = mode;
        ++include_depth;
        parse_entries(sub, dict, false, true);
        --include_depth;
        mode = saved;
    }

    // ---- directives -------------------------------------------------------------------

    //! Skips the rest of a directive's line (`#includeFunc streamLines`,
    //! `#includeFunc singleGraph(start=(0 0 0),` continued on the next line `fields=(U p))`):
    //! raw characters up to the end of the line where the parentheses are balanced (words
    //! may contain parentheses, so tokens would not show them).
    static void skip_line(FoamTokenizer& tok, std::size_t /*line*/)
    {
        const std::string_view rest = tok.buffer().substr(tok.offset()); // peek leaves offset()
        std::size_t n = 0;
        int depth = 0;
        for (; n < rest.size(); ++n)
        {
            const char c = rest[n];
            if (c == '(')
                ++depth;
            else if (c == ')')
                --depth;
            else if (c == '\n' && depth <= 0)
                break;
        }
        tok.read_raw(n);
    }

    //! Skips the argument of a code directive: a string (`#calc "..."`) or a `{ ... }` /
    //! `#{ ... #}` block (`#codeStream { code #{ ... #}; }`).
    static void skip_code_argument(FoamTokenizer& tok)
    {
        if (!tok.peek().is_punct('{'))
        {
            if (tok.peek().is_string() || tok.peek().is_word())
                tok.next();
            return;
        }
        int depth = 0;
        do
        {
            const FoamToken t = tok.next();
            if (t.is_end())
                return;
            if (t.is_punct('{'))
                ++depth;
            else if (t.is_punct('}'))
                --depth;
        } while (depth > 0);
    }

    void directive(FoamTokenizer& tok, FoamDictionary& dict, const FoamToken& d)
    {
        const std::string& w = d.text;
        if (w == "#include" || w == "#sinclude" || w == "#includeIfPresent")
            include(tok, dict, d);
        else if (options.skip_unsupported &&
                 (w == "#includeEtc" || w == "#includeFunc" || w == "#includeModel"))
            skip_line(tok, d.line);
        else if (w == "#includeEtc")
            throw tok.error_at(d.line, "'#includeEtc' (files of the OpenFOAM installation) is not "
                                       "supported: copy the entries into the dictionary");
        else if (w == "#includeFunc" || w == "#includeModel")
            throw tok.error_at(d.line, "'" + w +
                                           "' (OpenFOAM function objects/models) is not "
                                           "supported");
        else if (is_code_directive(w) && options.skip_unsupported)
            skip_code_argument(tok);
        else if (is_code_directive(w))
            throw_code_directive(tok, d.line, w);
        else if (w == "#inputMode")
        {
            const FoamToken m = tok.next();
            if (m.is_word("merge") || m.is_word("default"))
                mode = InputMode::merge;
            else if (m.is_word("overwrite"))
                mode = InputMode::overwrite;
            else if (m.is_word("protect"))
                mode = InputMode::protect;
            else if (m.is_word("warn"))
                mode = InputMode::warn;
            else if (m.is_word("error"))
                mode = InputMode::error;
            else
                throw tok.error_at(m.line, "unknown #inputMode " + m.describe() +
                                               " (expected merge, overwrite, protect, warn, "
                                               "error or default)");
        }
        else if (w == "#remove")
        {
            std::vector<FoamToken> keys;
            FoamToken t = tok.next();
            if (t.is_punct('('))
            {
                for (t = tok.next(); !t.is_punct(')'); t = tok.next())
                {
                    if (t.is_end())
                        throw tok.error_at(d.line, "unterminated key list after '#remove'");
                    keys.push_back(t);
                }
            }
            else
                keys.push_back(t);
            for (const FoamToken& k : keys)
            {
                if (!k.is_word() && !k.is_string())
                    throw tok.error_at(k.line, "expected a keyword after '#remove' but found " +
                                                   k.describe());
                auto& es = dict.entries_;
                if (k.is_string())
                {
                    const std::regex re =
                        compile_keyword_regex(tok, k, "regular expression after '#remove'");
                    std::erase_if(
                        es, [&](const FoamEntry& e)
                        { return std::regex_match(e.keyword_, re) || e.keyword_ == k.text; });
                }
                else
                    std::erase_if(es, [&](const FoamEntry& e) { return e.keyword_ == k.text; });
            }
        }
        else
            throw tok.error_at(d.line, "unknown directive '" + w + "'");
    }

    // ---- entries ----------------------------------------------------------------------

    void parse_entries(FoamTokenizer& tok, FoamDictionary& dict, bool nested,
                       bool is_include = false)
    {
        for (;;)
        {
            FoamToken key = tok.next();
            if (key.is_end() || key.is_punct('}'))
            {
                end_entries(tok, dict, key, nested, is_include);
                return;
            }
            if (key.is_punct(';'))
                continue; // a stray ';' is harmless
            if (key.is_word() && key.text.size() > 1 && key.text[0] == '#')
                directive(tok, dict, key);
            else if (key.is_word() && key.text.size() > 1 && key.text[0] == '$')
                merge_variable_dict(tok, dict, key);
            else if (key.type == TokenType::punctuation)
                throw tok.error_at(key.line, "expected a keyword but found " + key.describe());
            else
            {
                FoamEntry e = parse_entry(tok, dict, key);
                insert(dict, std::move(e), mode); // the mode after the entry (#inputMode inside)
            }
        }
    }

    // The end of a dictionary's entries: end of input (top level or an included file) or its
    // closing '}' (sub-dictionary).
    static void end_entries(const FoamTokenizer& tok, FoamDictionary& dict, const FoamToken& key,
                            bool nested, bool is_include)
    {
        if (key.is_end())
        {
            if (nested)
                throw tok.error_at(dict.line_, "unterminated dictionary '" + dict.scope_name() +
                                                   "' (no closing '}' before end of file)");
            if (!is_include)
                dict.end_line_ = tok.line();
            return;
        }
        if (!nested)
            throw tok.error_at(key.line, "unexpected '}' (no open dictionary)");
        dict.end_line_ = key.line;
    }

    // `$dict` at keyword position: merge a copy of that dictionary's entries. Like OpenFOAM,
    // an undefined name or a value there is ignored (with a warning). Not in a dictionary
    // read for a few entries (skip_unsupported: controlDict), whose skipped #includeEtc
    // files define such names (windAroundBuildings' runTimePostProcessing merges
    // `${..colourScheme.paraview}` from one): the warning would be about an entry the tool
    // never reads.
    void merge_variable_dict(FoamTokenizer& tok, FoamDictionary& dict, const FoamToken& key)
    {
        const FoamEntry* src = try_resolve(tok, key);
        if (!src || !src->is_dict())
        {
            if (!options.skip_unsupported)
                log::warning() << tok.path() << ":" << key.line << ": '" << key.text
                               << "' at keyword position "
                               << (src ? "names a value, not a dictionary" : "is undefined")
                               << "; ignored";
            tok.accept(';');
            return;
        }
        const FoamDictionary copy = src->dict();
        for (const FoamEntry& e : copy.entries_)
        {
            FoamEntry c = e;
            c.scope_ = dict.scope_;
            if (c.dict_)
                rescope(*c.dict_, child_scope(dict.scope_, c.keyword_));
            insert(dict, std::move(c), mode);
        }
        tok.accept(';');
    }

    // The entry starting with keyword `key`: a sub-dictionary `{ … }` or a value up to ';'.
    FoamEntry parse_entry(FoamTokenizer& tok, const FoamDictionary& dict, const FoamToken& key)
    {
        FoamEntry e;
        e.keyword_ = key.text;
        e.line_ = key.line;
        e.path_ = tok.path();
        e.scope_ = dict.scope_;
        if (key.is_string())
            e.regex_ = std::make_shared<const std::regex>(
                compile_keyword_regex(tok, key, "regular expression keyword"));
        const FoamToken& ahead = tok.peek();
        if (ahead.is_punct('{'))
            parse_sub_dict(tok, dict, key, ahead.offset, ahead.line, e);
        else if (ahead.is_word() && is_code_directive(ahead.text) && !options.skip_unsupported)
            throw_code_directive(tok, ahead.line, ahead.text);
        else
            parse_value(tok, e);
        return e;
    }

    // The sub-dictionary whose '{' is next (at open_offset, open_line), parsed recursively
    // with its own scope for $variables.
    void parse_sub_dict(FoamTokenizer& tok, const FoamDictionary& dict, const FoamToken& key,
                        std::size_t open_offset, std::size_t open_line, FoamEntry& e)
    {
        if (scopes.size() > max_dictionary_nesting)
            throw tok.error_at(open_line, "dictionary '" + child_scope(dict.scope_, key.text) +
                                              "' is nested deeper than " +
                                              std::to_string(max_dictionary_nesting) + " levels");
        tok.next();
        auto sub = std::make_unique<FoamDictionary>(tok.path(), child_scope(dict.scope_, key.text),
                                                    open_line);
        scopes.push_back(sub.get());
        try
        {
            parse_entries(tok, *sub, true);
        }
        catch (...)
        {
            scopes.pop_back();
            throw;
        }
        scopes.pop_back();
        e.source_ = std::string(tok.slice(open_offset, tok.offset()));
        e.dict_ = std::move(sub);
    }

    // ---- values -----------------------------------------------------------------------

    // The value of entry `e` up to its ';' (outside brackets): its tokens, with compounds
    // read whole and $variables expanded, and its source text.
    void parse_value(FoamTokenizer& tok, FoamEntry& e)
    {
        std::size_t first = std::string::npos;
        std::size_t last = 0;
        std::vector<std::size_t> open_lines; // the line of each open bracket
        for (;;)
        {
            FoamToken t = tok.next();
            if (t.is_end())
                throw_unterminated_value(tok, e, open_lines);
            if (open_lines.empty() && t.is_punct(';'))
                break;
            if (open_lines.empty() && t.is_punct('}'))
                throw tok.error_at(t.line, "expected ';' after the value of '" + e.keyword_ +
                                               "' but found '}'");
            if (first == std::string::npos)
                first = t.offset;
            last = t.end;
            if (t.type == TokenType::punctuation)
                track_brackets(tok, e, t, open_lines);
            else if (t.is_word())
            {
                const ValueWord word = expand_word(tok, e, t, last);
                if (word == ValueWord::whole_dict)
                    return;
                if (word == ValueWord::expanded)
                    continue;
            }
            FoamValueToken vt;
            static_cast<FoamToken&>(vt) = std::move(t);
            e.tokens_.push_back(std::move(vt));
        }
        if (first != std::string::npos)
            e.source_ = std::string(tok.slice(first, last));
    }

    [[noreturn]] static void throw_unterminated_value(const FoamTokenizer& tok, const FoamEntry& e,
                                                      const std::vector<std::size_t>& open_lines)
    {
        if (!open_lines.empty())
            throw tok.error_at(open_lines.back(), "unterminated list in entry '" + e.keyword_ +
                                                      "' (bracket opened here is never closed)");
        throw tok.error_at(e.line_,
                           "unexpected end of file in entry '" + e.keyword_ + "' (missing ';')");
    }

    // Brackets inside a value must balance.
    static void track_brackets(const FoamTokenizer& tok, const FoamEntry& e, const FoamToken& t,
                               std::vector<std::size_t>& open_lines)
    {
        if (t.punct == '(' || t.punct == '[' || t.punct == '{')
            open_lines.push_back(t.line);
        else if (t.punct == ')' || t.punct == ']' || t.punct == '}')
        {
            if (open_lines.empty())
                throw tok.error_at(t.line,
                                   "unbalanced " + t.describe() + " in entry '" + e.keyword_ + "'");
            open_lines.pop_back();
        }
    }

    // What expand_word did with a word of a value.
    enum class ValueWord
    {
        plain,      //!< nothing: the word is a value token
        expanded,   //!< stored in e.tokens_ (compound, code directive, $variable)
        whole_dict, //!< `key $dict;`: e is now a copy of that dictionary, and complete
    };

    // A word of a value: a compound (`List<scalar> N(…)`), a code directive, a $variable.
    // `last` is moved past what was read after the word.
    ValueWord expand_word(FoamTokenizer& tok, FoamEntry& e, const FoamToken& t, std::size_t& last)
    {
        if (is_compound_type(t.text))
        {
            const FoamToken& n = tok.peek();
            if (!n.is_label() && !n.is_punct('('))
                return ValueWord::plain;
            FoamValueToken vt;
            static_cast<FoamToken&>(vt) = t;
            vt.compound = std::make_shared<const FoamCompound>(
                read_compound(tok, t.text, options, e.keyword_));
            last = tok.offset();
            e.tokens_.push_back(std::move(vt));
            return ValueWord::expanded;
        }
        if (is_code_directive(t.text) && options.skip_unsupported)
        {
            // Kept as the directive word: reading this entry names it.
            FoamValueToken vt;
            static_cast<FoamToken&>(vt) = t;
            e.tokens_.push_back(std::move(vt));
            skip_code_argument(tok);
            last = tok.offset();
            return ValueWord::expanded;
        }
        if (is_code_directive(t.text))
            throw_code_directive(tok, t.line, t.text);
        if (t.text.size() > 1 && t.text[0] == '$')
            return expand_variable(tok, e, t);
        return ValueWord::plain;
    }

    // `$name` in a value: its tokens, or a dictionary's entries inside a list, or (alone)
    // a copy of the whole dictionary.
    ValueWord expand_variable(FoamTokenizer& tok, FoamEntry& e, const FoamToken& t)
    {
        const FoamEntry& src = resolve(tok, t);
        if (src.is_dict() && (!e.tokens_.empty() || !tok.peek().is_punct(';')))
        {
            // Inside a list (`fields ( rho { $meanOnly; } )`): splice the entries.
            dict_tokens(src.dict(), t.line, e.tokens_);
            return ValueWord::expanded;
        }
        if (src.is_dict())
        {
            // `key $dict;` copies the whole dictionary.
            tok.next();
            e.dict_ = std::make_unique<FoamDictionary>(src.dict());
            rescope(*e.dict_, child_scope(e.scope_, e.keyword_));
            e.source_ = t.text;
            return ValueWord::whole_dict;
        }
        for (const FoamValueToken& s : src.tokens_)
            e.tokens_.push_back(s);
        return ValueWord::expanded;
    }
};

namespace
{

void rescope(FoamDictionary& dict, const std::string& scope)
{
    detail_dictionary_access::set_scope(dict, scope);
    for (FoamEntry& e : detail_dictionary_access::entries(dict))
    {
        detail_dictionary_access::set_entry_scope(e, scope);
        if (e.is_dict())
            rescope(e.dict(), child_scope(scope, e.keyword()));
    }
}

} // namespace

void FoamDictionary::add(FoamEntry entry, bool merge)
{
    detail_dictionary_access::insert(*this, std::move(entry),
                                     merge ? detail_dictionary_access::InputMode::merge
                                           : detail_dictionary_access::InputMode::overwrite);
}

// ---------------------------------------------------------------------------------------
// Entry points

namespace
{

FoamDictionary parse_with(FoamTokenizer& tok, ParseOptions options, bool read_header)
{
    FoamDictionary dict(tok.path(), "", 1);
    if (read_header && has_header(tok))
    {
        FoamHeader h = parse_header(tok, false);
        options.binary = h.is_binary();
        options.label_bytes = h.label_bytes;
        options.scalar_bytes = h.scalar_bytes;
        dict.set_header(std::move(h));
    }
    detail_dictionary_access parser;
    parser.options = std::move(options);
    parser.case_dir = parser.options.case_dir.empty() ? derive_case_dir(fs::path(tok.path()))
                                                      : parser.options.case_dir;
    parser.scopes.push_back(&dict);
    parser.parse_entries(tok, dict, false);
    return dict;
}

} // namespace

FoamDictionary parse_dictionary(std::string_view text, const std::string& path,
                                const ParseOptions& options)
{
    FoamTokenizer tok(text, path);
    return parse_with(tok, options, true);
}

FoamDictionary parse_dictionary_body(FoamTokenizer& tokenizer, const ParseOptions& options)
{
    return parse_with(tokenizer, options, false);
}

FoamDictionary parse_dictionary_block(FoamTokenizer& tokenizer, const std::string& scope,
                                      const ParseOptions& options)
{
    const FoamToken open = tokenizer.next();
    if (!open.is_punct('{'))
        throw tokenizer.error_at(open.line, "expected '{' to start dictionary '" + scope +
                                                "' but found " + open.describe());
    FoamDictionary dict(tokenizer.path(), scope, open.line);
    detail_dictionary_access parser;
    parser.options = options;
    parser.case_dir =
        options.case_dir.empty() ? derive_case_dir(fs::path(tokenizer.path())) : options.case_dir;
    parser.scopes.push_back(&dict);
    parser.parse_entries(tokenizer, dict, true);
    return dict;
}

FoamDictionary read_dictionary(const std::filesystem::path& path, ParseOptions options)
{
    std::optional<std::string> text =
        options.read_file ? options.read_file(path) : read_file_plain_or_gz(path);
    if (!text)
        throw IoError("cannot open dictionary '" + path.string() + "' (nor '" + path.string() +
                      ".gz'): no such file");
    return parse_dictionary(*text, path.string(), options);
}

} // namespace meshmorph::io
