// SPDX-License-Identifier: GPL-3.0-or-later
// The closest-point AABB tree over a triangle surface.
#include "meshmorph/core/triangle_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "meshmorph/core/exceptions.h"

namespace meshmorph
{
namespace
{

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

//! Relative size of the distance band in which triangles tie (SurfaceTree::tie_tolerance).
constexpr double relative_tie_tolerance = 1e-9;

double surface_size(const Points& vertices)
{
    const double diagonal = (vertices.colwise().maxCoeff() - vertices.colwise().minCoeff()).norm();
    return std::max(diagonal, vertices.cwiseAbs().maxCoeff());
}

} // namespace

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
    tie_tolerance_ = relative_tie_tolerance * surface_size(surface_.vertices);
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

namespace
{

//! A triangle's closest point to the query, kept while it may lie within the tie band.
struct Candidate
{
    double distance;
    Index triangle;
    Vector3 point;
};

//! The nearest of `near` whose point lies within `radius` of `centre` (lowest triangle on
//! equal distances).
const Candidate& nearest_around(const std::vector<Candidate>& near, const Vector3& centre,
                                double radius)
{
    const Candidate* best = nullptr;
    for (const Candidate& c : near)
        if ((c.point - centre).norm() <= radius &&
            (!best || c.distance < best->distance ||
             (c.distance == best->distance && c.triangle < best->triangle)))
            best = &c;
    return *best;
}

//! The tie rule over the candidates within the band of the nearest distance `best`. Near
//! an edge or vertex the neighbouring triangles' closest points fall within the band too
//! (a foot e from an edge is only e^2 / 2d farther from it), but they are the same place:
//! within `same_place` = 2 sqrt(2 d tol) + tol of the nearest point, the exact nearest wins.
//! Only when the band holds another place (the two slopes of a symmetric target) does the
//! lowest triangle index choose the place; within it, again the exact nearest point.
SurfacePoint choose(const std::vector<Candidate>& near, double best, double tol)
{
    SurfacePoint result;
    if (near.empty())
        return result;
    const double same_place = 2.0 * std::sqrt(2.0 * best * tol) + tol;
    const Candidate* nearest = &near.front();
    const Candidate* first_listed = &near.front();
    for (const Candidate& c : near)
    {
        if (c.distance < nearest->distance ||
            (c.distance == nearest->distance && c.triangle < nearest->triangle))
            nearest = &c;
        if (c.triangle < first_listed->triangle)
            first_listed = &c;
    }
    const bool another_place = std::any_of(
        near.begin(), near.end(),
        [&](const Candidate& c) { return (c.point - nearest->point).norm() > same_place; });
    const Candidate& chosen =
        another_place ? nearest_around(near, first_listed->point, same_place) : *nearest;
    result.point = chosen.point;
    result.triangle = chosen.triangle;
    result.distance = chosen.distance;
    return result;
}

} // namespace

SurfacePoint SurfaceTree::closest_point(const Vector3& query) const
{
    // One traversal keeps every triangle that may lie within the tie band of the nearest
    // (pruned against the best distance plus the band), then the tie rule picks.
    thread_local std::vector<Candidate> near;
    near.clear();
    double best = std::numeric_limits<double>::infinity();
    const auto reach2 = [&]
    {
        const double r = best + tie_tolerance_;
        return r * r;
    };
    // Depth is O(log n) for the median split; 128 entries cover any realistic surface.
    std::array<Index, 128> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
        const Node& node = nodes_[stack[--top]];
        if (box_distance_squared(query, node.lo, node.hi) > reach2())
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
                const double d = (x - query).norm();
                if (d > best + tie_tolerance_)
                    continue;
                best = std::min(best, d);
                near.push_back({d, t, x});
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
    // Candidates kept before `best` dropped may have left the band since.
    std::erase_if(near, [&](const Candidate& c) { return c.distance > best + tie_tolerance_; });
    return choose(near, best, tie_tolerance_);
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
