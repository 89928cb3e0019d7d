// SPDX-License-Identifier: GPL-3.0-or-later
// OpenFOAM dictionaries: the data model and the typed getters (parsing: foam_dictionary_parser.cpp,
// compound lists: foam_compound.cpp).
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

std::string display_scope(const std::string& scope, const std::string& path)
{
    if (!scope.empty())
        return scope;
    const std::string name = fs::path(path).filename().string();
    return name.empty() ? path : name;
}

} // namespace

// ---------------------------------------------------------------------------------------
// FoamCompound, FoamEntry

std::size_t FoamCompound::size() const
{
    switch (kind)
    {
    case Kind::label:
    case Kind::boolean:
        return labels.size();
    case Kind::scalar:
        return scalars.size();
    case Kind::vector:
        return scalars.size() / 3;
    case Kind::word:
        return words.size();
    }
    return 0;
}

FoamEntry::FoamEntry(const FoamEntry& other)
    : keyword_(other.keyword_), regex_(other.regex_),
      dict_(other.dict_ ? std::make_unique<FoamDictionary>(*other.dict_) : nullptr),
      tokens_(other.tokens_), source_(other.source_), path_(other.path_), line_(other.line_),
      scope_(other.scope_)
{
}

FoamEntry& FoamEntry::operator=(const FoamEntry& other)
{
    if (this != &other)
    {
        FoamEntry copy(other);
        *this = std::move(copy);
    }
    return *this;
}

FoamEntry::~FoamEntry() = default;

bool FoamEntry::matches(const std::string& name) const
{
    if (regex_)
        return std::regex_match(name, *regex_);
    return keyword_ == name;
}

ParseError FoamEntry::error(const std::string& msg) const
{
    return ParseError(path_, line_,
                      "keyword '" + keyword_ + "' in dictionary '" + display_scope(scope_, path_) +
                          "': " + msg);
}

// ---------------------------------------------------------------------------------------
// FoamDictionary

FoamDictionary::FoamDictionary(std::string path, std::string scope, std::size_t line)
    : path_(std::move(path)), scope_(std::move(scope)), line_(line), end_line_(line)
{
}

std::string FoamDictionary::scope_name() const
{
    return display_scope(scope_, path_);
}

const FoamEntry* FoamDictionary::find(const std::string& key) const
{
    for (const FoamEntry& e : entries_)
        if (!e.is_regex() && e.keyword_ == key)
            return &e;
    for (auto it = entries_.rbegin(); it != entries_.rend(); ++it)
        if (it->is_regex() && std::regex_match(key, *it->regex_))
            return &*it;
    return nullptr;
}

FoamEntry* FoamDictionary::find(const std::string& key)
{
    return const_cast<FoamEntry*>(static_cast<const FoamDictionary*>(this)->find(key));
}

const FoamEntry& FoamDictionary::entry(const std::string& key) const
{
    const FoamEntry* e = find(key);
    if (!e)
        throw ParseError(path_, line_ == 0 ? 1 : line_,
                         "keyword '" + key + "' is undefined in dictionary '" + scope_name() + "'");
    return *e;
}

bool FoamDictionary::is_dict(const std::string& key) const
{
    const FoamEntry* e = find(key);
    return e && e->is_dict();
}

const FoamDictionary& FoamDictionary::sub_dict(const std::string& key) const
{
    const FoamEntry& e = entry(key);
    if (!e.is_dict())
        throw e.error("expected a sub-dictionary '{ ... }' but found a value");
    return e.dict();
}

const FoamDictionary* FoamDictionary::find_dict(const std::string& key) const
{
    const FoamEntry* e = find(key);
    return (e && e->is_dict()) ? &e->dict() : nullptr;
}

std::vector<std::string> FoamDictionary::keys() const
{
    std::vector<std::string> out;
    out.reserve(entries_.size());
    for (const FoamEntry& e : entries_)
        out.push_back(e.keyword_);
    return out;
}

ParseError FoamDictionary::error(const std::string& msg) const
{
    return ParseError(path_, line_ == 0 ? 1 : line_, msg);
}

void FoamDictionary::check_keywords(const std::vector<std::string>& allowed,
                                    const std::string& what,
                                    const std::vector<std::string>& helpers) const
{
    const auto listed = [](const std::vector<std::string>& v, const std::string& k)
    { return std::find(v.begin(), v.end(), k) != v.end(); };
    for (const FoamEntry& e : entries_)
        if (!listed(allowed, e.keyword()) && !listed(helpers, e.keyword()))
        {
            std::string list;
            for (const std::string& a : allowed)
                list += (list.empty() ? "" : " ") + a;
            throw e.error("unknown keyword for " + what + " (valid: " + list +
                          "; a helper entry must be used somewhere as $" + e.keyword() + ")");
        }
}

namespace
{

//! The first keyword of each `$...` variable in `text`, without scope prefixes.
void collect_variables(const std::string& text, std::vector<std::string>& names)
{
    const auto is_name = [](char c)
    { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; };
    for (std::size_t at = text.find('$'); at != std::string::npos; at = text.find('$', at + 1))
    {
        std::size_t i = at + 1;
        if (i < text.size() && text[i] == '{')
            ++i;
        while (i < text.size() && (text[i] == ':' || text[i] == '/' || text[i] == '.'))
            ++i;
        std::size_t end = i;
        while (end < text.size() && is_name(text[end]))
            ++end;
        if (end > i)
            names.push_back(text.substr(i, end - i));
    }
}

} // namespace

std::vector<std::string> FoamDictionary::referenced_variables() const
{
    std::vector<std::string> names;
    for (const FoamEntry& e : entries_)
        collect_variables(e.source_text(), names);
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    return names;
}

bool FoamDictionary::remove(const std::string& keyword)
{
    for (auto it = entries_.begin(); it != entries_.end(); ++it)
        if (it->keyword_ == keyword)
        {
            entries_.erase(it);
            return true;
        }
    return false;
}

// ---------------------------------------------------------------------------------------
// Typed conversion of entry values

namespace
{

class Cursor
{
public:
    Cursor(const FoamEntry& e, std::size_t first) : e_(e), t_(e.tokens()), i_(first)
    {
        if (e.is_dict())
            throw e.error("expected a value but found a sub-dictionary");
    }
    const FoamValueToken* peek() const { return i_ < t_.size() ? &t_[i_] : nullptr; }
    const FoamValueToken& take(const std::string& expected)
    {
        if (i_ >= t_.size())
            fail(expected);
        return t_[i_++];
    }
    [[noreturn]] void fail(const std::string& expected) const
    {
        const std::string found = i_ < t_.size() ? t_[i_].describe() : std::string("end of value");
        throw e_.error("expected " + expected + " but found " + found);
    }
    void expect_punct(char c, const std::string& context)
    {
        const FoamValueToken* t = peek();
        if (!t || !t->is_punct(c))
            fail(std::string("'") + c + "' " + context);
        ++i_;
    }
    void finish(const std::string& what) const
    {
        if (i_ != t_.size())
            throw e_.error("unexpected " + t_[i_].describe() + " after " + what);
    }
    const FoamEntry& entry() const { return e_; }

private:
    const FoamEntry& e_;
    const std::vector<FoamValueToken>& t_;
    std::size_t i_;
};

double take_scalar(Cursor& c)
{
    const FoamValueToken& t = c.take("a number");
    if (t.is_number())
        return t.scalar;
    if (t.is_word())
    {
        if (t.text == "inf" || t.text == "Inf" || t.text == "INF")
            return std::numeric_limits<double>::infinity();
        if (t.text == "-inf" || t.text == "-Inf" || t.text == "-INF")
            return -std::numeric_limits<double>::infinity();
        if (t.text == "nan" || t.text == "NaN" || t.text == "NAN")
            return std::numeric_limits<double>::quiet_NaN();
    }
    throw c.entry().error("expected a number but found " + t.describe());
}

std::int64_t take_label(Cursor& c)
{
    const FoamValueToken& t = c.take("an integer");
    if (!t.is_label())
        throw c.entry().error("expected an integer but found " + t.describe());
    return t.label;
}

std::string take_string(Cursor& c)
{
    const FoamValueToken& t = c.take("a word or string");
    if (!(t.is_word() && !t.is_compound()) && !t.is_string())
        throw c.entry().error("expected a word or string but found " + t.describe());
    return t.text;
}

bool take_bool(Cursor& c)
{
    const FoamValueToken& t = c.take("a switch (yes/no, on/off, true/false)");
    if (t.is_label() && (t.label == 0 || t.label == 1))
        return t.label == 1;
    if (t.is_word())
    {
        const std::string& w = t.text;
        if (w == "yes" || w == "on" || w == "true" || w == "y" || w == "t")
            return true;
        if (w == "no" || w == "off" || w == "false" || w == "n" || w == "f" || w == "none")
            return false;
    }
    throw c.entry().error("expected a switch (yes/no, on/off, true/false) but found " +
                          t.describe());
}

Vector3 take_vector(Cursor& c)
{
    c.expect_punct('(', "starting a vector (x y z)");
    Vector3 v;
    for (int k = 0; k < 3; ++k)
        v[k] = take_scalar(c);
    c.expect_punct(')', "closing a 3-component vector (x y z)");
    return v;
}

// A list in any of its spellings. `from_compound` fills `out` from a compound token and
// returns false if the compound's kind does not fit.
template <class T, class ReadOne, class FromCompound>
std::vector<T> take_list(Cursor& c, const std::string& what, ReadOne read_one,
                         FromCompound from_compound)
{
    std::vector<T> out;
    const FoamValueToken* t = c.peek();
    if (!t)
        c.fail("a list of " + what);
    if (t->is_compound())
    {
        if (!from_compound(*t->compound, out))
            throw c.entry().error("expected a list of " + what + " but found a " +
                                  t->compound->type_word);
        c.take(what);
        return out;
    }
    std::int64_t n = -1;
    if (t->is_label())
    {
        n = t->label;
        if (n < 0)
            throw c.entry().error("negative list size " + std::to_string(n));
        c.take(what);
        const FoamValueToken* u = c.peek();
        // An empty list is written `0` alone in binary format (decomposePar's `value
        // nonuniform 0;` for a patch with no points on a processor).
        if (n == 0 && !(u && (u->is_punct('(') || u->is_punct('{'))))
            return out;
        if (u && u->is_punct('{'))
        {
            c.take(what);
            const T v = read_one(c);
            c.expect_punct('}', "closing a uniform list N{value}");
            if (n > max_uniform_list_size)
                throw c.entry().error("uniform list of " + std::to_string(n) +
                                      " elements exceeds the plausible size " +
                                      std::to_string(max_uniform_list_size));
            out.assign(static_cast<std::size_t>(n), v);
            return out;
        }
    }
    c.expect_punct('(', n >= 0 ? "after the list size" : "starting a list");
    for (;;)
    {
        const FoamValueToken* u = c.peek();
        if (u && u->is_punct(')'))
        {
            c.take(")");
            break;
        }
        out.push_back(read_one(c));
    }
    if (n >= 0 && out.size() != static_cast<std::size_t>(n))
        throw c.entry().error("list declares " + std::to_string(n) + " elements but has " +
                              std::to_string(out.size()));
    return out;
}

std::vector<std::int64_t> take_label_list(Cursor& c)
{
    return take_list<std::int64_t>(c, "integers", take_label,
                                   [](const FoamCompound& k, std::vector<std::int64_t>& out)
                                   {
                                       if (k.kind != FoamCompound::Kind::label &&
                                           k.kind != FoamCompound::Kind::boolean)
                                           return false;
                                       out = k.labels;
                                       return true;
                                   });
}

std::int32_t narrow(const FoamEntry& e, std::int64_t v)
{
    if (v < std::numeric_limits<std::int32_t>::min() ||
        v > std::numeric_limits<std::int32_t>::max())
        throw e.error("integer " + std::to_string(v) + " does not fit in 32 bits");
    return static_cast<std::int32_t>(v);
}

} // namespace

template <> double FoamEntry::get<double>(std::size_t first) const
{
    Cursor c(*this, first);
    const double v = take_scalar(c);
    c.finish("the number");
    return v;
}

template <> float FoamEntry::get<float>(std::size_t first) const
{
    return static_cast<float>(get<double>(first));
}

template <> std::int64_t FoamEntry::get<std::int64_t>(std::size_t first) const
{
    Cursor c(*this, first);
    const std::int64_t v = take_label(c);
    c.finish("the integer");
    return v;
}

template <> std::int32_t FoamEntry::get<std::int32_t>(std::size_t first) const
{
    return narrow(*this, get<std::int64_t>(first));
}

template <> bool FoamEntry::get<bool>(std::size_t first) const
{
    Cursor c(*this, first);
    const bool v = take_bool(c);
    c.finish("the switch");
    return v;
}

template <> std::string FoamEntry::get<std::string>(std::size_t first) const
{
    Cursor c(*this, first);
    std::string v = take_string(c);
    c.finish("the word");
    return v;
}

template <> Vector3 FoamEntry::get<Vector3>(std::size_t first) const
{
    Cursor c(*this, first);
    const Vector3 v = take_vector(c);
    c.finish("the vector");
    return v;
}

template <> std::vector<double> FoamEntry::get<std::vector<double>>(std::size_t first) const
{
    Cursor c(*this, first);
    std::vector<double> v = take_list<double>(c, "numbers", take_scalar,
                                              [](const FoamCompound& k, std::vector<double>& out)
                                              {
                                                  if (k.kind == FoamCompound::Kind::scalar)
                                                      out = k.scalars;
                                                  else if (k.kind == FoamCompound::Kind::label)
                                                      out.assign(k.labels.begin(), k.labels.end());
                                                  else
                                                      return false;
                                                  return true;
                                              });
    c.finish("the list");
    return v;
}

template <>
std::vector<std::int64_t> FoamEntry::get<std::vector<std::int64_t>>(std::size_t first) const
{
    Cursor c(*this, first);
    std::vector<std::int64_t> v = take_label_list(c);
    c.finish("the list");
    return v;
}

template <>
std::vector<std::int32_t> FoamEntry::get<std::vector<std::int32_t>>(std::size_t first) const
{
    const std::vector<std::int64_t> wide = get<std::vector<std::int64_t>>(first);
    std::vector<std::int32_t> out(wide.size());
    for (std::size_t i = 0; i < wide.size(); ++i)
        out[i] = narrow(*this, wide[i]);
    return out;
}

template <>
std::vector<std::string> FoamEntry::get<std::vector<std::string>>(std::size_t first) const
{
    Cursor c(*this, first);
    std::vector<std::string> v =
        take_list<std::string>(c, "words", take_string,
                               [](const FoamCompound& k, std::vector<std::string>& out)
                               {
                                   if (k.kind != FoamCompound::Kind::word)
                                       return false;
                                   out = k.words;
                                   return true;
                               });
    c.finish("the list");
    return v;
}

template <> std::vector<Vector3> FoamEntry::get<std::vector<Vector3>>(std::size_t first) const
{
    Cursor c(*this, first);
    std::vector<Vector3> v = take_list<Vector3>(
        c, "vectors", take_vector,
        [](const FoamCompound& k, std::vector<Vector3>& out)
        {
            if (k.kind != FoamCompound::Kind::vector)
                return false;
            out.resize(k.size());
            for (std::size_t i = 0; i < out.size(); ++i)
                out[i] = Vector3(k.scalars[3 * i], k.scalars[3 * i + 1], k.scalars[3 * i + 2]);
            return true;
        });
    c.finish("the list");
    return v;
}

} // namespace meshmorph::io
