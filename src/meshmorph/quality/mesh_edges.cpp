// SPDX-License-Identifier: GPL-3.0-or-later
// Edge counts without building the edge list: every undirected edge (p, q), p <= q, is found
// once from its smaller point p by walking p's faces; it is a boundary edge when any
// boundary face uses it.
#include "meshmorph/quality/mesh_edges.h"

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

namespace
{

//! The edges (p, q), q >= p, of one point p at a time, with per-thread scratch space.
class PointEdges
{
public:
    explicit PointEdges(Index n_points)
        : mark_(static_cast<std::size_t>(n_points), -1), slot_(static_cast<std::size_t>(n_points))
    {
    }

    //! Collect p's edges into others() / is_boundary().
    void collect(const PolyMesh& mesh, const CompactList& point_faces, Index p)
    {
        is_boundary_.clear();
        others_.clear();
        const std::span<const Index> faces_of_p = point_faces[p];
        for (std::size_t k = 0; k < faces_of_p.size(); ++k)
        {
            const Index f = faces_of_p[k];
            if (k > 0 && faces_of_p[k - 1] == f)
                continue; // p repeated in f: all its occurrences are seen below
            const std::span<const Index> face = mesh.faces[f];
            const std::size_t n = face.size();
            const bool boundary_face = f >= mesh.n_internal_faces();
            for (std::size_t i = 0; i < n; ++i)
                if (face[i] == p)
                    for (const Index q : {face[(i + 1) % n], face[(i + n - 1) % n]})
                        if (q >= p)
                            add(p, q, boundary_face);
        }
    }
    const std::vector<Index>& others() const { return others_; }
    const std::vector<char>& is_boundary() const { return is_boundary_; }

private:
    void add(Index p, Index q, bool boundary_face)
    {
        if (mark_[q] != p)
        {
            mark_[q] = p;
            slot_[q] = static_cast<Index>(is_boundary_.size());
            is_boundary_.push_back(0);
            others_.push_back(q);
        }
        is_boundary_[slot_[q]] |= boundary_face;
    }

    std::vector<Index> mark_; // mark_[q] == p: edge (p, q) already seen
    std::vector<Index> slot_; // its index in is_boundary_
    std::vector<char> is_boundary_;
    std::vector<Index> others_;
};

} // namespace

EdgeCounts count_edges(const PolyMesh& mesh, const CompactList& point_faces,
                       const std::vector<char>& boundary)
{
    const Index n_points = mesh.n_points();
    std::int64_t n_edges = 0, n_internal_edges = 0, n_one = 0, n_two = 0;
#pragma omp parallel if (mesh.n_faces() > detail::parallel_threshold) \
    reduction(+ : n_edges, n_internal_edges, n_one, n_two)
    {
        PointEdges edges(n_points);
#pragma omp for schedule(dynamic, detail::loop_piece)
        for (Index p = 0; p < n_points; ++p)
        {
            edges.collect(mesh, point_faces, p);
            n_edges += static_cast<std::int64_t>(edges.others().size());
            for (std::size_t k = 0; k < edges.others().size(); ++k)
            {
                if (edges.is_boundary()[k])
                    continue;
                ++n_internal_edges;
                const int nb = boundary[p] + boundary[edges.others()[k]];
                n_one += nb == 1;
                n_two += nb == 2;
            }
        }
    }
    return {n_edges, n_internal_edges, n_one, n_two};
}

} // namespace meshmorph
