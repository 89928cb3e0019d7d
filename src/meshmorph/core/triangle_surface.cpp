// SPDX-License-Identifier: GPL-3.0-or-later
// STL/OBJ readers (gzip-transparent through zlib) and the closest-point AABB tree.
#include "meshmorph/core/triangle_surface.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>

#include <zlib.h>

#include "meshmorph/core/exceptions.h"

namespace meshmorph
{
namespace
{

// The whole file, decompressed if it is gzip (zlib reads plain files unchanged).
std::string read_file(const std::filesystem::path& path)
{
    gzFile file = gzopen(path.c_str(), "rb");
    if (file == nullptr)
        throw IoError(path.string() + ": cannot open: " + std::strerror(errno));
    std::string data;
    std::array<char, 1 << 16> buffer;
    while (true)
    {
        const int n = gzread(file, buffer.data(), static_cast<unsigned>(buffer.size()));
        if (n < 0)
        {
            int code = 0;
            const std::string message = gzerror(file, &code);
            gzclose(file);
            throw IoError(path.string() + ": read error: " + message);
        }
        if (n == 0)
            break;
        data.append(buffer.data(), static_cast<std::size_t>(n));
    }
    gzclose(file);
    return data;
}

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

// Closest point on segment [p, q] to x.
Vector3 closest_on_segment(const Vector3& x, const Vector3& p, const Vector3& q)
{
    const Vector3 d = q - p;
    const double dd = d.squaredNorm();
    if (!(dd > 0.0))
        return p;
    const double t = std::clamp((x - p).dot(d) / dd, 0.0, 1.0);
    return p + t * d;
}

double box_distance_squared(const Vector3& q, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
{
    double d = 0;
    for (int k = 0; k < 3; ++k)
    {
        const double e = std::max({lo[k] - q[k], 0.0, q[k] - hi[k]});
        d += e * e;
    }
    return d;
}

constexpr Index leaf_size = 4;

} // namespace

TriangleSurface read_stl(const std::filesystem::path& path)
{
    const std::string data = read_file(path);
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

TriangleSurface read_obj(const std::filesystem::path& path)
{
    const std::string data = read_file(path);
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

Vector3 closest_point_on_triangle(const Vector3& q, const Vector3& a, const Vector3& b,
                                  const Vector3& c)
{
    const Vector3 ab = b - a;
    const Vector3 ac = c - a;
    // Degenerate (zero-area) triangle: the Voronoi-region test divides by zero; use edges.
    if (!(ab.cross(ac).squaredNorm() > 0.0))
    {
        const Vector3 candidates[3] = {closest_on_segment(q, a, b), closest_on_segment(q, b, c),
                                       closest_on_segment(q, c, a)};
        const Vector3* best = &candidates[0];
        for (const Vector3& x : candidates)
            if ((x - q).squaredNorm() < (*best - q).squaredNorm())
                best = &x;
        return *best;
    }
    const Vector3 ap = q - a;
    const double d1 = ab.dot(ap);
    const double d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0)
        return a;
    const Vector3 bp = q - b;
    const double d3 = ab.dot(bp);
    const double d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3)
        return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
        return a + (d1 / (d1 - d3)) * ab;
    const Vector3 cp = q - c;
    const double d5 = ab.dot(cp);
    const double d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6)
        return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
        return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

SurfaceTree::SurfaceTree(TriangleSurface surface) : surface_(std::move(surface))
{
    const Index n = surface_.n_triangles();
    if (n == 0)
        throw InvalidInput("SurfaceTree: surface has no triangles");
    if (!surface_.vertices.allFinite())
        throw InvalidInput("SurfaceTree: surface has non-finite vertex coordinates");
    for (Index t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k)
            if (surface_.triangles(t, k) < 0 || surface_.triangles(t, k) >= surface_.n_vertices())
                throw InvalidInput("SurfaceTree: triangle " + std::to_string(t) +
                                   " has vertex label " + std::to_string(surface_.triangles(t, k)) +
                                   " outside [0, " + std::to_string(surface_.n_vertices()) + ")");
    std::vector<Eigen::Vector3d> centroids(static_cast<std::size_t>(n));
    for (Index t = 0; t < n; ++t)
        centroids[t] = (surface_.vertices.row(surface_.triangles(t, 0)) +
                        surface_.vertices.row(surface_.triangles(t, 1)) +
                        surface_.vertices.row(surface_.triangles(t, 2)))
                           .transpose() /
                       3.0;
    order_.resize(static_cast<std::size_t>(n));
    for (Index t = 0; t < n; ++t)
        order_[t] = t;
    nodes_.reserve(static_cast<std::size_t>(4 * (n / leaf_size + 1)));
    nodes_.emplace_back();
    build(0, 0, n, centroids);
}

void SurfaceTree::build(Index node, Index begin, Index end,
                        const std::vector<Eigen::Vector3d>& centroids)
{
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    Eigen::Vector3d clo = lo;
    Eigen::Vector3d chi = hi;
    for (Index i = begin; i < end; ++i)
    {
        for (int k = 0; k < 3; ++k)
        {
            const Eigen::Vector3d p =
                surface_.vertices.row(surface_.triangles(order_[i], k)).transpose();
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
        clo = clo.cwiseMin(centroids[order_[i]]);
        chi = chi.cwiseMax(centroids[order_[i]]);
    }
    nodes_[node].lo = lo;
    nodes_[node].hi = hi;
    if (end - begin <= leaf_size)
    {
        nodes_[node].first = begin;
        nodes_[node].count = end - begin;
        return;
    }
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    const Index mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](Index a, Index b) { return centroids[a][axis] < centroids[b][axis]; });
    // Both children get consecutive slots before either subtree is built (indices, not
    // references: nodes_ may reallocate during the recursion).
    const Index left = static_cast<Index>(nodes_.size());
    nodes_.resize(nodes_.size() + 2);
    nodes_[node].first = left;
    nodes_[node].count = 0;
    build(left, begin, mid, centroids);
    build(left + 1, mid, end, centroids);
}

SurfacePoint SurfaceTree::closest_point(const Vector3& query) const
{
    SurfacePoint best;
    double best_d2 = std::numeric_limits<double>::infinity();
    // Depth is O(log n) for the median split; 128 entries cover any realistic surface.
    std::array<Index, 128> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
        const Node& node = nodes_[stack[--top]];
        if (box_distance_squared(query, node.lo, node.hi) >= best_d2)
            continue;
        if (node.count > 0)
        {
            for (Index i = node.first; i < node.first + node.count; ++i)
            {
                const Index t = order_[i];
                const Vector3 a = surface_.vertices.row(surface_.triangles(t, 0)).transpose();
                const Vector3 b = surface_.vertices.row(surface_.triangles(t, 1)).transpose();
                const Vector3 c = surface_.vertices.row(surface_.triangles(t, 2)).transpose();
                const Vector3 x = closest_point_on_triangle(query, a, b, c);
                const double d2 = (x - query).squaredNorm();
                if (d2 < best_d2)
                {
                    best_d2 = d2;
                    best.point = x;
                    best.triangle = t;
                }
            }
            continue;
        }
        const Index l = node.first;
        const Index r = node.first + 1;
        const double dl = box_distance_squared(query, nodes_[l].lo, nodes_[l].hi);
        const double dr = box_distance_squared(query, nodes_[r].lo, nodes_[r].hi);
        // Push the farther child first so the nearer one is searched first.
        const bool left_first = dl <= dr;
        if (top + 2 > static_cast<int>(stack.size()))
            throw std::logic_error("SurfaceTree: traversal stack overflow");
        stack[top++] = left_first ? r : l;
        stack[top++] = left_first ? l : r;
    }
    best.distance = std::sqrt(best_d2);
    return best;
}

Points SurfaceTree::closest_points(const Eigen::Ref<const Points>& queries) const
{
    const Index n = static_cast<Index>(queries.rows());
    Points result(n, 3);
#pragma omp parallel for schedule(dynamic, 256) if (n > 2000)
    for (Index i = 0; i < n; ++i)
        result.row(i) = closest_point(queries.row(i).transpose()).point.transpose();
    return result;
}

} // namespace meshmorph
