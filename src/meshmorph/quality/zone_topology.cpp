// SPDX-License-Identifier: GPL-3.0-or-later
// Surface topology of patches and faceZones, cellZone addressing.
#include "meshmorph/quality/zone_topology.h"

#include <algorithm>
#include <array>
#include <numeric>

#include "meshmorph/quality/check_result.h"
#include "meshmorph/quality/disjoint_sets.h"
#include "meshmorph/quality/mesh_edges.h"

namespace meshmorph
{

namespace
{

//! Whether some edge is used once (open), and the points of edges used more than twice.
std::pair<bool, std::vector<Index>> edge_use(const PolyMesh& mesh, const std::vector<Index>& faces)
{
    std::vector<std::uint64_t> edges;
    for (Index f : faces)
    {
        const std::span<const Index> face = mesh.faces[f];
        for (std::size_t i = 0; i < face.size(); ++i)
            edges.push_back(packed_edge(face[i], face[(i + 1) % face.size()]));
    }
    std::sort(edges.begin(), edges.end());
    bool has_open = false;
    std::vector<Index> over;
    for (std::size_t i = 0; i < edges.size();)
    {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i])
            ++j;
        has_open = has_open || j - i == 1;
        if (j - i > 2)
        {
            over.push_back(static_cast<Index>(edges[i] >> 32));
            over.push_back(static_cast<Index>(edges[i] & 0xffffffffu));
        }
        i = j;
    }
    return {has_open, as_set(std::move(over))};
}

//! The two neighbours of point p in face f (-1 if p is not in f).
std::array<Index, 2> neighbours_in_face(const PolyMesh& mesh, Index f, Index p)
{
    const std::span<const Index> face = mesh.faces[f];
    const std::size_t n = face.size();
    std::array<Index, 2> nb{-1, -1};
    for (std::size_t i = 0; i < n; ++i)
        if (face[i] == p)
        {
            nb[0] = face[(i + 1) % n];
            nb[1] = face[(i + n - 1) % n];
        }
    return nb;
}

//! Whether the faces `pf` (indices into `faces`) around point p form more than one fan of
//! faces sharing an edge through p.
bool several_fans(const PolyMesh& mesh, const std::vector<Index>& faces,
                  const std::vector<Index>& pf, Index p)
{
    detail::DisjointSets fans(static_cast<Index>(pf.size()));
    for (std::size_t a = 0; a < pf.size(); ++a)
    {
        const std::array<Index, 2> na = neighbours_in_face(mesh, faces[pf[a]], p);
        for (std::size_t b = a + 1; b < pf.size(); ++b)
        {
            const std::array<Index, 2> nb = neighbours_in_face(mesh, faces[pf[b]], p);
            bool share = false;
            for (Index x : na)
                for (Index y : nb)
                    share = share || (x == y && x >= 0);
            if (share)
                fans.link(fans.find(static_cast<Index>(a)), fans.find(static_cast<Index>(b)));
        }
    }
    return fans.count() > 1;
}

//! For a closed surface: the points whose faces form several fans.
std::vector<Index> shared_points(const PolyMesh& mesh, const std::vector<Index>& faces,
                                 const std::vector<Index>& points)
{
    std::vector<Index> local(static_cast<std::size_t>(mesh.n_points()), -1);
    for (std::size_t i = 0; i < points.size(); ++i)
        local[points[i]] = static_cast<Index>(i);
    std::vector<std::vector<Index>> point_faces_local(points.size());
    for (std::size_t k = 0; k < faces.size(); ++k)
        for (Index p : mesh.faces[faces[k]])
            point_faces_local[local[p]].push_back(static_cast<Index>(k));
    std::vector<Index> shared;
    for (std::size_t pi = 0; pi < points.size(); ++pi)
        if (several_fans(mesh, faces, point_faces_local[pi], points[pi]))
            shared.push_back(points[pi]);
    return shared;
}

} // namespace

SurfaceTopology surface_topology(const PolyMesh& mesh, std::string name,
                                 const std::vector<Index>& faces)
{
    SurfaceTopology t;
    t.name = std::move(name);
    t.n_faces = static_cast<Index>(faces.size());
    std::vector<Index> points;
    for (Index f : faces)
        for (Index p : mesh.faces[f])
            points.push_back(p);
    points = as_set(std::move(points));
    t.n_points = static_cast<Index>(points.size());
    if (!points.empty())
    {
        t.bb_min = mesh.points.row(points[0]).transpose();
        t.bb_max = t.bb_min;
        for (Index p : points)
        {
            t.bb_min = t.bb_min.cwiseMin(mesh.points.row(p).transpose());
            t.bb_max = t.bb_max.cwiseMax(mesh.points.row(p).transpose());
        }
    }
    if (faces.empty())
    {
        t.type = "ok (empty)";
        return t;
    }
    auto [has_open, over] = edge_use(mesh, faces);
    t.edge_points = std::move(over);
    if (!t.edge_points.empty())
        t.type = "multiply connected (shared edge)";
    else if (has_open)
        t.type = "ok (non-closed singly connected)";
    else if (t.fan_points = shared_points(mesh, faces, points); !t.fan_points.empty())
        t.type = "multiply connected (shared point)";
    else
        t.type = "ok (closed singly connected)";
    return t;
}

std::vector<SurfaceTopology> patch_topology(const PolyMesh& mesh)
{
    std::vector<SurfaceTopology> rows;
    for (const Patch& p : mesh.patches)
    {
        std::vector<Index> faces(static_cast<std::size_t>(p.n_faces));
        std::iota(faces.begin(), faces.end(), p.start_face);
        rows.push_back(surface_topology(mesh, p.name, faces));
    }
    return rows;
}

std::vector<SurfaceTopology> face_zone_topology(const PolyMesh& mesh)
{
    std::vector<SurfaceTopology> rows;
    for (const Zone& z : mesh.face_zones)
        rows.push_back(surface_topology(mesh, z.name, z.labels));
    return rows;
}

std::vector<CellZoneSummary>
cell_zone_summaries(const PolyMesh& mesh, const CompactList& cell_faces, const MeshGeometry& g)
{
    std::vector<CellZoneSummary> rows;
    std::vector<char> in_zone(static_cast<std::size_t>(mesh.n_points()), 0);
    for (const Zone& z : mesh.cell_zones)
    {
        std::fill(in_zone.begin(), in_zone.end(), 0);
        // An empty zone keeps OpenFOAM's boundBox::invertedBox, (ROOTVGREAT) (-ROOTVGREAT):
        // checkMesh prints (1e+150 1e+150 1e+150) (-1e+150 -1e+150 -1e+150) for it.
        CellZoneSummary s{z.name,
                          static_cast<Index>(z.labels.size()),
                          0,
                          0,
                          Vector3::Constant(constants::rootvgreat),
                          Vector3::Constant(-constants::rootvgreat)};
        for (Index cell : z.labels)
        {
            s.volume += g.cell_volumes[cell];
            for (Index f : cell_faces[cell])
                for (Index p : mesh.faces[f])
                    if (!in_zone[p])
                    {
                        in_zone[p] = 1;
                        ++s.n_points;
                        s.bb_min = s.bb_min.cwiseMin(mesh.points.row(p).transpose());
                        s.bb_max = s.bb_max.cwiseMax(mesh.points.row(p).transpose());
                    }
        }
        rows.push_back(std::move(s));
    }
    return rows;
}

} // namespace meshmorph
