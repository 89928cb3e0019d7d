// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/design/case_fingerprint.h"

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "meshmorph/io/foam_dictionary.h"

namespace meshmorph::design
{

namespace
{

class Fnv1a
{
public:
    //! FNV-1a over 8-byte words, then the remaining bytes (a word at a time: the points
    //! and topology of a large mesh are hashed in a few milliseconds).
    void add(const void* data, std::size_t n)
    {
        const auto* b = static_cast<const unsigned char*>(data);
        std::size_t i = 0;
        for (; i + 8 <= n; i += 8)
        {
            std::uint64_t word;
            std::memcpy(&word, b + i, 8);
            h_ = (h_ ^ word) * prime;
        }
        for (; i < n; ++i)
            h_ = (h_ ^ b[i]) * prime;
    }
    template <class T> void add_value(const T& v) { add(&v, sizeof v); }
    std::string hex() const
    {
        char text[17];
        std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h_));
        return text;
    }

private:
    static constexpr std::uint64_t prime = 0x100000001b3ULL;
    std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

//! morphDict keys that judge a variant after the fields are combined (untangle its new
//! invalid cells and how many, refuse its new check failures) or that only a one-off morph
//! reads (maxNonOrtho): editing one leaves the set-up current.
bool judges_variants_only(const io::FoamEntry& e, int depth)
{
    return depth == 0 && (e.keyword() == "untangle" || e.keyword() == "maxUntangleCells" ||
                          e.keyword() == "newCheckFailures" || e.keyword() == "maxNonOrtho");
}

void add_dictionary(Fnv1a& f, const io::FoamDictionary& dict, int depth = 0)
{
    for (const io::FoamEntry& e : dict.entries())
    {
        if (judges_variants_only(e, depth))
            continue;
        f.add(e.keyword().data(), e.keyword().size() + 1);
        if (e.is_dict())
        {
            f.add("{", 1);
            add_dictionary(f, e.dict(), depth + 1);
            f.add("}", 1);
            continue;
        }
        for (const io::FoamValueToken& t : e.tokens())
            f.add(t.text.data(), t.text.size() + 1);
        f.add(";", 1);
    }
}

} // namespace

std::string dictionary_fingerprint(const io::FoamDictionary& dict)
{
    Fnv1a f;
    add_dictionary(f, dict);
    return f.hex();
}

std::string fingerprint(std::string_view bytes)
{
    Fnv1a f;
    f.add(bytes.data(), bytes.size());
    return f.hex();
}

std::string points_fingerprint(const Points& points)
{
    Fnv1a f;
    f.add_value(std::int64_t(points.rows()));
    f.add(points.data(), sizeof(double) * std::size_t(points.size()));
    return f.hex();
}

std::string topology_fingerprint(const PolyMesh& mesh)
{
    Fnv1a f;
    const auto add_labels = [&f](const std::vector<Index>& labels)
    {
        f.add_value(std::int64_t(labels.size()));
        f.add(labels.data(), sizeof(Index) * labels.size());
    };
    add_labels(mesh.faces.offsets);
    add_labels(mesh.faces.values);
    add_labels(mesh.owner);
    add_labels(mesh.neighbour);
    for (const Patch& p : mesh.patches)
    {
        f.add(p.name.data(), p.name.size() + 1); // with its terminator: names stay apart
        f.add_value(std::int64_t(p.start_face));
        f.add_value(std::int64_t(p.n_faces));
    }
    return f.hex();
}

} // namespace meshmorph::design
