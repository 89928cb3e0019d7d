// SPDX-License-Identifier: GPL-3.0-or-later
#include "paper_common.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <set>

#include "meshmorph/core/exceptions.h"

namespace paper
{

std::string Options::get(const std::string& key, const std::string& fallback) const
{
    const auto it = value.find(key);
    return it == value.end() ? fallback : it->second;
}

double Options::number(const std::string& key, double fallback) const
{
    const auto it = value.find(key);
    if (it == value.end())
        return fallback;
    std::size_t used = 0;
    const double v = std::stod(it->second, &used);
    if (used != it->second.size())
        throw meshmorph::InvalidInput("-" + key + ": not a number: '" + it->second + "'");
    return v;
}

void write_json(const std::filesystem::path& path, const Json& json)
{
    if (path.has_parent_path())
        std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path);
    out << json.dump(1) << '\n';
    if (!out)
        throw meshmorph::IoError("cannot write " + path.string());
}

namespace
{
double round_to(double v, int digits)
{
    if (!std::isfinite(v) || v == 0.0)
        return v;
    const double scale = std::pow(10.0, digits - 1 - int(std::floor(std::log10(std::abs(v)))));
    return std::round(v * scale) / scale;
}
} // namespace

Json rows_json(const Points& p, int digits)
{
    Json a = Json::array();
    for (Eigen::Index i = 0; i < p.rows(); ++i)
        a.push_back(
            {round_to(p(i, 0), digits), round_to(p(i, 1), digits), round_to(p(i, 2), digits)});
    return a;
}

Json rows_json(const Triangles& t)
{
    Json a = Json::array();
    for (Eigen::Index i = 0; i < t.rows(); ++i)
        a.push_back({t(i, 0), t(i, 1), t(i, 2)});
    return a;
}

Json vector_json(const Eigen::VectorXd& v, int digits)
{
    Json a = Json::array();
    for (Eigen::Index i = 0; i < v.size(); ++i)
    {
        if (std::isfinite(v[i]))
            a.push_back(round_to(v[i], digits));
        else
            a.push_back(nullptr);
    }
    return a;
}

Surface grid_plane(int n)
{
    Surface s;
    s.vertices.resize(Index(n) * n, 3);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            s.vertices.row(i + Index(n) * j) =
                Eigen::RowVector3d(double(i) / (n - 1), double(j) / (n - 1), 0.0);
    s.triangles.resize(2 * Index(n - 1) * (n - 1), 3);
    Index t = 0;
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i)
        {
            const Index a = i + Index(n) * j, b = a + 1, c = a + n, d = c + 1;
            if ((i + j) % 2 == 0)
            {
                s.triangles.row(t++) << a, b, d;
                s.triangles.row(t++) << a, d, c;
            }
            else
            {
                s.triangles.row(t++) << a, b, c;
                s.triangles.row(t++) << b, d, c;
            }
        }
    return s;
}

Surface icosphere(int level, double radius)
{
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vector3> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                              {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                              {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    std::vector<std::array<Index, 3>> f = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (Vector3& p : v)
        p.normalize();
    for (int l = 0; l < level; ++l)
    {
        std::map<std::pair<Index, Index>, Index> mid;
        const auto midpoint = [&](Index a, Index b)
        {
            const auto key = std::minmax(a, b);
            const auto it = mid.find(key);
            if (it != mid.end())
                return it->second;
            v.push_back((v[std::size_t(a)] + v[std::size_t(b)]).normalized());
            const Index id = Index(v.size()) - 1;
            mid.emplace(key, id);
            return id;
        };
        std::vector<std::array<Index, 3>> next;
        next.reserve(4 * f.size());
        for (const auto& t : f)
        {
            const Index ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]),
                        ca = midpoint(t[2], t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({t[1], bc, ab});
            next.push_back({t[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        f = std::move(next);
    }
    Surface s;
    s.vertices.resize(Index(v.size()), 3);
    for (std::size_t i = 0; i < v.size(); ++i)
        s.vertices.row(Index(i)) = radius * v[i].transpose();
    s.triangles.resize(Index(f.size()), 3);
    for (std::size_t i = 0; i < f.size(); ++i)
        s.triangles.row(Index(i)) << f[i][0], f[i][1], f[i][2];
    return s;
}

Points fibonacci_sphere(Index m, const Vector3& centre, double radius)
{
    Points h(m, 3);
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (Index i = 0; i < m; ++i)
    {
        const double z = 1.0 - 2.0 * (double(i) + 0.5) / double(m);
        const double r = std::sqrt(1.0 - z * z);
        h.row(i) = centre.transpose() + radius * Eigen::RowVector3d(r * std::cos(golden * i),
                                                                    r * std::sin(golden * i), z);
    }
    return h;
}

Points random_box(Index n, unsigned seed, double lo, double hi)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(lo, hi);
    Points p(n, 3);
    for (Index i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            p(i, c) = u(gen);
    return p;
}

double max_row_norm(const Points& p)
{
    return p.rows() == 0 ? 0.0 : p.rowwise().norm().maxCoeff();
}

Residual residual(const meshmorph::SpaceDeformation& d, const Points& handles,
                  const Points& displacements)
{
    const Points got = meshmorph::displacements(d, handles);
    const Eigen::VectorXd e = (got - displacements).rowwise().norm();
    Residual r;
    r.max_abs = e.size() ? e.maxCoeff() : 0.0;
    r.rms_abs = e.size() ? std::sqrt(e.squaredNorm() / double(e.size())) : 0.0;
    const double scale = max_row_norm(displacements);
    r.max_rel = scale > 0.0 ? r.max_abs / scale : r.max_abs;
    r.rms_rel = scale > 0.0 ? r.rms_abs / scale : r.rms_abs;
    return r;
}

Json residual_json(const Residual& r)
{
    return {
        {"maxAbs", r.max_abs}, {"rmsAbs", r.rms_abs}, {"maxRel", r.max_rel}, {"rmsRel", r.rms_rel}};
}

meshmorph::FfdDeformation qualitative_ffd(const meshmorph::FfdLattice& lattice,
                                          const Points& handles, const Points& displacements)
{
    const Points& c = lattice.control_points();
    // Lattice spacing: the smallest distance between neighbouring control planes.
    double spacing = std::numeric_limits<double>::max();
    for (int a = 0; a < 3; ++a)
    {
        const auto& n = lattice.counts();
        const Index step = a == 0 ? 1 : a == 1 ? n[0] : Index(n[0]) * n[1];
        spacing = std::min(spacing, (c.row(step) - c.row(0)).norm());
    }
    Points dc = Points::Zero(c.rows(), 3);
    for (Index p = 0; p < c.rows(); ++p)
    {
        Index best = -1;
        double best_d2 = spacing * spacing;
        for (Index i = 0; i < handles.rows(); ++i)
        {
            const double d2 = (handles.row(i) - c.row(p)).squaredNorm();
            if (d2 < best_d2)
            {
                best_d2 = d2;
                best = i;
            }
        }
        if (best >= 0)
            dc.row(p) = displacements.row(best);
    }
    meshmorph::FfdDeformation ffd(lattice);
    ffd.set_control_displacements(dc);
    return ffd;
}

CurvatureStats curvature_stats(const Surface& s, const Eigen::VectorXd& H,
                               const std::vector<char>& mask)
{
    CurvatureStats c;
    std::vector<double> values;
    for (Index i = 0; i < H.size(); ++i)
        if (mask[std::size_t(i)] && std::isfinite(H[i]))
            values.push_back(H[i]);
    c.vertices = Index(values.size());
    if (values.empty())
        return c;
    double sum = 0.0;
    for (double v : values)
        sum += v;
    c.mean = sum / double(values.size());
    std::sort(values.begin(), values.end());
    c.max = values.back();
    c.p99 = values[std::min(values.size() - 1, std::size_t(0.99 * double(values.size())))];

    const auto counted = [&](Index v) { return mask[std::size_t(v)] && std::isfinite(H[v]); };
    std::vector<std::set<Index>> ring(std::size_t(s.vertices.rows()));
    for (Index t = 0; t < s.triangles.rows(); ++t)
    {
        const Index a = s.triangles(t, 0), b = s.triangles(t, 1), d = s.triangles(t, 2);
        for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, d}, std::pair{d, a}})
        {
            ring[std::size_t(x)].insert(y);
            ring[std::size_t(y)].insert(x);
        }
        if (!counted(a) || !counted(b) || !counted(d))
            continue;
        const Vector3 pa = s.vertices.row(a), pb = s.vertices.row(b), pd = s.vertices.row(d);
        const Vector3 n2 = (pb - pa).cross(pd - pa); // |n2| = 2 A
        const double area2 = n2.norm();
        if (area2 <= 0.0)
            continue;
        const Vector3 n = n2 / area2;
        // grad of the P1 hat function of a vertex: n x (opposite edge) / (2 A).
        const Vector3 grad =
            (H[a] * n.cross(pd - pb) + H[b] * n.cross(pa - pd) + H[d] * n.cross(pb - pa)) / area2;
        const double hm = (H[a] + H[b] + H[d]) / 3.0;
        c.bending += 0.5 * area2 * hm * hm;
        c.variation += 0.5 * area2 * grad.squaredNorm();
    }
    for (Index v = 0; v < s.vertices.rows(); ++v)
    {
        if (!counted(v) || ring[std::size_t(v)].empty())
            continue;
        bool is_max = true;
        for (Index w : ring[std::size_t(v)])
            if (!std::isfinite(H[w]) || H[w] >= H[v])
            {
                is_max = false;
                break;
            }
        c.local_maxima += is_max ? 1 : 0;
    }
    return c;
}

Json curvature_json(const CurvatureStats& c)
{
    return {{"vertices", c.vertices},
            {"mean", c.mean},
            {"max", c.max},
            {"p99", c.p99},
            {"bending", c.bending},
            {"variation", c.variation},
            {"localMaxima", c.local_maxima}};
}

} // namespace paper
