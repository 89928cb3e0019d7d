// SPDX-License-Identifier: GPL-3.0-or-later
// STL and OBJ readers; the bytes come from foam_file's whole-file reader (plain or gzip).
#include "meshmorph/io/surface_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_file.h"

namespace meshmorph::io
{
namespace
{

bool iequals(std::string_view a, std::string_view b)
{
    return a.size() == b.size() &&
           std::equal(a.begin(), a.end(), b.begin(),
                      [](char x, char y)
                      {
                          return std::tolower(static_cast<unsigned char>(x)) ==
                                 std::tolower(static_cast<unsigned char>(y));
                      });
}

bool parse_double(std::string_view text, double& value)
{
    const char* end = text.data() + text.size();
    const std::from_chars_result r = std::from_chars(text.data(), end, value);
    return r.ec == std::errc() && r.ptr == end && std::isfinite(value);
}

// Merges vertices with bit-identical coordinates (-0 and +0 are the same point).
class VertexMerger
{
public:
    Index add(const Vector3& p)
    {
        std::array<std::uint64_t, 3> key;
        for (int k = 0; k < 3; ++k)
        {
            const double v = p[k] == 0.0 ? 0.0 : p[k];
            std::memcpy(&key[k], &v, sizeof(double));
        }
        const auto [it, inserted] = index_.try_emplace(key, static_cast<Index>(points_.size()));
        if (inserted)
            points_.push_back(p);
        return it->second;
    }
    Points points() const
    {
        Points result(static_cast<Eigen::Index>(points_.size()), 3);
        for (std::size_t i = 0; i < points_.size(); ++i)
            result.row(static_cast<Eigen::Index>(i)) = points_[i].transpose();
        return result;
    }

private:
    struct Hash
    {
        std::size_t operator()(const std::array<std::uint64_t, 3>& k) const
        {
            std::uint64_t h = 0x9e3779b97f4a7c15ull;
            for (std::uint64_t v : k)
                h = (h ^ v) * 0x100000001b3ull + (h >> 29);
            return static_cast<std::size_t>(h);
        }
    };
    std::unordered_map<std::array<std::uint64_t, 3>, Index, Hash> index_;
    std::vector<Vector3> points_;
};

Triangles to_triangles(const std::vector<std::array<Index, 3>>& list)
{
    Triangles t(static_cast<Eigen::Index>(list.size()), 3);
    for (std::size_t i = 0; i < list.size(); ++i)
        t.row(static_cast<Eigen::Index>(i)) << list[i][0], list[i][1], list[i][2];
    return t;
}

// Whitespace tokenizer over a buffer that counts lines.
class Tokens
{
public:
    explicit Tokens(std::string_view text) : text_(text) {}
    // Next token, or empty at the end; line() is then the token's line.
    std::string_view next()
    {
        skip_space();
        const std::size_t begin = pos_;
        token_line_ = line_;
        while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])))
            ++pos_;
        return text_.substr(begin, pos_ - begin);
    }
    void skip_line()
    {
        while (pos_ < text_.size() && text_[pos_] != '\n')
            ++pos_;
    }
    std::size_t line() const { return token_line_; }

private:
    void skip_space()
    {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_])))
        {
            if (text_[pos_] == '\n')
                ++line_;
            ++pos_;
        }
    }
    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    std::size_t token_line_ = 1;
};

TriangleSurface read_ascii_stl(const std::filesystem::path& path, std::string_view text)
{
    Tokens tokens(text);
    VertexMerger merger;
    std::vector<std::array<Index, 3>> triangles;
    const auto fail = [&](const std::string& message) -> void
    { throw ParseError(path.string(), tokens.line(), message); };
    const auto expect = [&](std::string_view keyword)
    {
        const std::string_view t = tokens.next();
        if (!iequals(t, keyword))
            fail("expected '" + std::string(keyword) + "', found " +
                 (t.empty() ? std::string("end of file") : "'" + std::string(t) + "'"));
    };
    const auto number = [&]()
    {
        const std::string_view t = tokens.next();
        double v = 0;
        if (!parse_double(t, v))
            fail("expected a finite number, found " +
                 (t.empty() ? std::string("end of file") : "'" + std::string(t) + "'"));
        return v;
    };

    std::string_view t = tokens.next();
    while (!t.empty())
    {
        if (!iequals(t, "solid"))
            fail("expected 'solid', found '" + std::string(t) + "'");
        tokens.skip_line(); // the solid's name may contain spaces
        while (true)
        {
            t = tokens.next();
            if (iequals(t, "endsolid"))
            {
                tokens.skip_line();
                break;
            }
            if (!iequals(t, "facet"))
                fail("expected 'facet' or 'endsolid', found " +
                     (t.empty() ? std::string("end of file") : "'" + std::string(t) + "'"));
            expect("normal");
            for (int k = 0; k < 3; ++k)
                tokens
                    .next(); // normals are recomputed from the vertex order; some writers emit nan
            expect("outer");
            expect("loop");
            std::vector<Index> loop;
            while (true)
            {
                t = tokens.next();
                if (iequals(t, "endloop"))
                    break;
                if (!iequals(t, "vertex"))
                    fail("expected 'vertex' or 'endloop', found " +
                         (t.empty() ? std::string("end of file") : "'" + std::string(t) + "'"));
                Vector3 p;
                for (int k = 0; k < 3; ++k)
                    p[k] = number();
                loop.push_back(merger.add(p));
            }
            if (loop.size() < 3)
                fail("facet with " + std::to_string(loop.size()) + " vertices");
            for (std::size_t i = 1; i + 1 < loop.size(); ++i)
                triangles.push_back({loop[0], loop[i], loop[i + 1]});
            expect("endfacet");
        }
        t = tokens.next();
    }
    if (triangles.empty())
        throw ParseError(path.string(), 0, "no triangles in ASCII STL");
    return {merger.points(), to_triangles(triangles)};
}

TriangleSurface read_binary_stl(const std::filesystem::path& path, std::string_view data,
                                std::uint32_t n)
{
    VertexMerger merger;
    std::vector<std::array<Index, 3>> triangles;
    triangles.reserve(n);
    for (std::uint32_t t = 0; t < n; ++t)
    {
        const std::size_t offset = 84 + 50 * static_cast<std::size_t>(t);
        float f[12];
        std::memcpy(f, data.data() + offset, sizeof(f)); // little-endian IEEE (x86, arm64)
        std::array<Index, 3> tri;
        for (int v = 0; v < 3; ++v)
        {
            const Vector3 p(f[3 + 3 * v], f[4 + 3 * v], f[5 + 3 * v]);
            if (!p.allFinite())
                throw ParseError(path.string(), 0,
                                 "byte " + std::to_string(offset + 12 + 12 * v) + ": triangle " +
                                     std::to_string(t) + " has a non-finite vertex");
            tri[v] = merger.add(p);
        }
        triangles.push_back(tri);
    }
    if (triangles.empty())
        throw ParseError(path.string(), 0, "byte 80: binary STL with 0 triangles");
    return {merger.points(), to_triangles(triangles)};
}

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

} // namespace

TriangleSurface read_stl(const std::filesystem::path& file)
{
    const FileBuffer buffer = read_foam_file(file);
    const std::filesystem::path& path = buffer.path; // the file read: X or X.gz
    const std::string& data = buffer.data;
    if (data.size() >= 84)
    {
        std::uint32_t n = 0;
        std::memcpy(&n, data.data() + 80, 4);
        if (data.size() == 84 + 50 * static_cast<std::uint64_t>(n))
            return read_binary_stl(path, data, n);
    }
    std::size_t first = 0;
    while (first < data.size() && std::isspace(static_cast<unsigned char>(data[first])))
        ++first;
    if (data.size() - first >= 5 && iequals(std::string_view(data).substr(first, 5), "solid"))
        return read_ascii_stl(path, data);
    if (data.size() < 84)
        throw ParseError(path.string(), 0,
                         "byte " + std::to_string(data.size()) +
                             ": not an STL file (no 'solid' and shorter than a binary header)");
    std::uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);
    throw ParseError(path.string(), 0,
                     "byte 80: not an STL file: no 'solid' keyword, and a binary STL with " +
                         std::to_string(n) + " triangles would have " +
                         std::to_string(84 + 50 * static_cast<std::uint64_t>(n)) + " bytes, not " +
                         std::to_string(data.size()) + " (truncated?)");
}

TriangleSurface read_obj(const std::filesystem::path& file)
{
    const FileBuffer buffer = read_foam_file(file);
    const std::filesystem::path& path = buffer.path; // the file read: X or X.gz
    const std::string& data = buffer.data;
    std::vector<Vector3> vertices;
    std::vector<std::array<Index, 3>> triangles;
    std::size_t line_no = 0;
    std::size_t pos = 0;
    std::vector<Index> face;
    while (pos < data.size())
    {
        ++line_no;
        std::size_t end = data.find('\n', pos);
        if (end == std::string::npos)
            end = data.size();
        std::string_view line(data.data() + pos, end - pos);
        pos = end + 1;
        if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
            line = line.substr(0, hash);
        Tokens tokens(line);
        const std::string_view kind = tokens.next();
        const auto fail = [&](const std::string& message)
        { throw ParseError(path.string(), line_no, message); };
        if (kind == "v")
        {
            Vector3 p;
            for (int k = 0; k < 3; ++k)
            {
                const std::string_view t = tokens.next();
                if (!parse_double(t, p[k]))
                    fail("expected a finite vertex coordinate, found " +
                         (t.empty() ? std::string("end of line") : "'" + std::string(t) + "'"));
            }
            vertices.push_back(p);
        }
        else if (kind == "f")
        {
            face.clear();
            for (std::string_view t = tokens.next(); !t.empty(); t = tokens.next())
            {
                const std::string_view index_text = t.substr(0, t.find('/'));
                long long index = 0;
                const auto r = std::from_chars(index_text.data(),
                                               index_text.data() + index_text.size(), index);
                if (r.ec != std::errc() || r.ptr != index_text.data() + index_text.size() ||
                    index == 0)
                    fail("bad face vertex '" + std::string(t) + "'");
                const long long n = static_cast<long long>(vertices.size());
                const long long resolved = index > 0 ? index - 1 : n + index;
                if (resolved < 0 || resolved >= n)
                    fail("face vertex " + std::to_string(index) + " out of range (" +
                         std::to_string(n) + " vertices so far)");
                face.push_back(static_cast<Index>(resolved));
            }
            if (face.size() < 3)
                fail("face with " + std::to_string(face.size()) + " vertices");
            for (std::size_t i = 1; i + 1 < face.size(); ++i)
                triangles.push_back({face[0], face[i], face[i + 1]});
        }
        // Anything else (vn, vt, g, o, s, usemtl, mtllib, l, blank) is not geometry we use.
    }
    if (triangles.empty())
        throw ParseError(path.string(), 0, "no faces in OBJ file");
    TriangleSurface surface;
    surface.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
    for (std::size_t i = 0; i < vertices.size(); ++i)
        surface.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
    surface.triangles = to_triangles(triangles);
    return surface;
}

TriangleSurface read_surface(const std::filesystem::path& path)
{
    std::filesystem::path p = path;
    if (lower(p.extension().string()) == ".gz")
        p = p.stem();
    const std::string ext = lower(p.extension().string());
    if (ext == ".stl")
        return read_stl(path);
    if (ext == ".obj")
        return read_obj(path);
    throw InvalidInput(path.string() + ": unsupported surface format '" + ext +
                       "' (supported: .stl, .obj, optionally .gz)");
}

} // namespace meshmorph::io
