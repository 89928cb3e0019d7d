// SPDX-License-Identifier: GPL-3.0-or-later
// checkMesh's checks (OpenFOAM v1912 primitiveMeshCheck / polyMeshCheck / checkTopology /
// checkGeometry) and report text; see docs/checkmesh-spec.md for every formula and line.
//
// Parallelism: per-face and per-cell values are computed into arrays with OpenMP; all
// reductions (sums, minima, counts) then run serially in storage order, so the report does
// not depend on the number of threads (nor on the schedule: the heavier -allGeometry /
// -allTopology loops are scheduled dynamically, which copes better with a loaded machine).
// Integer counts are the only OpenMP reductions (exact in any order).
#include "meshmorph/quality/check_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/foam_vector.h"
#include "meshmorph/quality/scaled_jacobian.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

std::string format_scalar(double value, int precision)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
    return buffer;
}

namespace
{

constexpr double small = constants::small;
constexpr double vsmall = constants::vsmall;
constexpr double rootvsmall = constants::rootvsmall;
constexpr double great = constants::great;

//! Writes report lines with OpenFOAM's number formatting.
class Printer
{
public:
    explicit Printer(int precision) : p_(precision) {}
    std::string s(double v) const { return format_scalar(v, p_); }
    std::string v(const FoamVector& x) const
    {
        return "(" + s(x.x) + " " + s(x.y) + " " + s(x.z) + ")";
    }
    std::string v(const Eigen::Vector3d& x) const { return v(FoamVector{x.x(), x.y(), x.z()}); }
    //! Justified in `width` columns (std::setw). checkMesh's tables are left-justified,
    //! except after a polyhedra breakdown: v1912 sets ios::right there and never resets
    //! it, so every later table is right-justified (reproduced, see right_justify).
    std::string w(const std::string& text, std::size_t width) const
    {
        if (text.size() >= width)
            return text;
        const std::string fill(width - text.size(), ' ');
        return right_justify ? fill + text : text + fill;
    }
    bool right_justify = false;
    std::ostringstream out;

private:
    int p_;
};

//! Sorted distinct labels.
std::vector<Index> as_set(std::vector<Index> labels)
{
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    return labels;
}

std::vector<Index> flagged(const std::vector<char>& mask)
{
    std::vector<Index> labels;
    for (std::size_t i = 0; i < mask.size(); ++i)
        if (mask[i])
            labels.push_back(static_cast<Index>(i));
    return labels;
}

//! Point -> faces in CSR form; each point's faces in ascending order (a face listing a
//! point twice appears twice).
CompactList point_faces_of(const PolyMesh& mesh)
{
    CompactList pf;
    pf.offsets.assign(static_cast<std::size_t>(mesh.n_points()) + 1, 0);
    for (Index p : mesh.faces.values)
        ++pf.offsets[p + 1];
    std::partial_sum(pf.offsets.begin(), pf.offsets.end(), pf.offsets.begin());
    pf.values.resize(mesh.faces.values.size());
    std::vector<Index> fill(pf.offsets.begin(), pf.offsets.end() - 1);
    for (Index f = 0; f < mesh.n_faces(); ++f)
        for (Index p : mesh.faces[f])
            pf.values[fill[p]++] = f;
    return pf;
}

struct Context
{
    const PolyMesh& mesh;
    const CompactList& cell_faces;
    const MeshGeometry& g;
    const CheckMeshSettings& settings;
    QualityReport& report;
    Printer& pr;

    //! Point -> faces addressing (CSR, each point's faces ascending), built on first use.
    const CompactList& point_faces()
    {
        if (point_faces_.size() != mesh.n_points())
            point_faces_ = point_faces_of(mesh);
        return point_faces_;
    }
    CompactList point_faces_;

    void fail(const std::string& name)
    {
        ++report.failed_checks;
        report.failed_check_names.push_back(name);
    }
    //! Record a set and print checkMesh's "<<Writing" line (only when sets are written).
    void set(const std::string& name, MeshSet::Kind kind, std::vector<Index> labels,
             const std::string& what, bool print_when_empty = false)
    {
        labels = as_set(std::move(labels));
        if (labels.empty() && !print_when_empty)
            return;
        if (settings.report_sets)
            pr.out << "  <<Writing " << labels.size() << " " << what << " to set " << name << "\n";
        if (!labels.empty())
            report.sets.push_back({name, kind, std::move(labels)});
    }
};

// ---------------------------------------------------------------------------------------
// Topology helpers

using Edge = std::pair<Index, Index>;

//! An undirected edge as one sortable integer (smaller label in the high half).
std::uint64_t packed_edge(Index a, Index b)
{
    const std::uint32_t lo = static_cast<std::uint32_t>(std::min(a, b));
    const std::uint32_t hi = static_cast<std::uint32_t>(std::max(a, b));
    return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

//! Surface topology of a set of faces (a patch or a faceZone), as PrimitivePatch sees it.
struct SurfaceTopology
{
    Index n_points = 0;
    std::string type;
    Eigen::Vector3d bb_min, bb_max;
};

SurfaceTopology surface_topology(const PolyMesh& mesh, const std::vector<Index>& faces)
{
    SurfaceTopology t;
    std::vector<Index> points;
    std::vector<std::uint64_t> edges;
    for (Index f : faces)
    {
        const std::span<const Index> face = mesh.faces[f];
        for (std::size_t i = 0; i < face.size(); ++i)
        {
            points.push_back(face[i]);
            edges.push_back(packed_edge(face[i], face[(i + 1) % face.size()]));
        }
    }
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
    std::sort(edges.begin(), edges.end());
    bool has_open = false, has_over = false;
    for (std::size_t i = 0; i < edges.size();)
    {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i])
            ++j;
        const std::size_t count = j - i;
        if (count == 1)
            has_open = true;
        else if (count > 2)
            has_over = true;
        i = j;
    }
    if (has_over)
    {
        t.type = "multiply connected (shared edge)";
        return t;
    }
    if (has_open)
    {
        t.type = "ok (non-closed singly connected)";
        return t;
    }
    // Closed: every point's faces must form a single edge-connected fan.
    std::vector<std::vector<Index>> point_faces_local;
    std::vector<Index> local(static_cast<std::size_t>(mesh.n_points()), -1);
    for (std::size_t i = 0; i < points.size(); ++i)
        local[points[i]] = static_cast<Index>(i);
    point_faces_local.resize(points.size());
    for (std::size_t k = 0; k < faces.size(); ++k)
        for (Index p : mesh.faces[faces[k]])
            point_faces_local[local[p]].push_back(static_cast<Index>(k));
    bool shared_point = false;
    for (std::size_t pi = 0; pi < points.size() && !shared_point; ++pi)
    {
        const Index p = points[pi];
        const std::vector<Index>& pf = point_faces_local[pi];
        // Union faces sharing an edge through p.
        std::vector<Index> comp(pf.size());
        std::iota(comp.begin(), comp.end(), 0);
        const auto find = [&](Index a)
        {
            while (comp[a] != a)
                a = comp[a] = comp[comp[a]];
            return a;
        };
        const auto neighbours_of = [&](Index f)
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
        };
        for (std::size_t a = 0; a < pf.size(); ++a)
        {
            const std::array<Index, 2> na = neighbours_of(faces[pf[a]]);
            for (std::size_t b = a + 1; b < pf.size(); ++b)
            {
                const std::array<Index, 2> nb = neighbours_of(faces[pf[b]]);
                bool share = false;
                for (Index x : na)
                    for (Index y : nb)
                        share = share || (x == y && x >= 0);
                if (share)
                    comp[find(static_cast<Index>(a))] = find(static_cast<Index>(b));
            }
        }
        Index roots = 0;
        for (std::size_t a = 0; a < pf.size(); ++a)
            roots += find(static_cast<Index>(a)) == static_cast<Index>(a);
        shared_point = roots > 1;
    }
    t.type = shared_point ? "multiply connected (shared point)" : "ok (closed singly connected)";
    return t;
}

// ---------------------------------------------------------------------------------------

std::vector<CellShape> mesh_stats(Context& c)
{
    const PolyMesh& mesh = c.mesh;
    std::ostringstream& out = c.pr.out;
    out << "Mesh stats\n";
    out << "    points:           " << mesh.n_points() << "\n";
    // Points are "ordered" when all boundary points come last.
    const std::vector<char> boundary = boundary_point_mask(mesh);
    const Index n_boundary = static_cast<Index>(std::count(boundary.begin(), boundary.end(), 1));
    const Index n_internal_points = mesh.n_points() - n_boundary;
    bool ordered = true;
    for (Index p = 0; p < mesh.n_points() && ordered; ++p)
        if (!boundary[p] && p >= n_internal_points)
            ordered = false;
    if (ordered)
    {
        out << "    internal points:  " << n_internal_points << "\n";
        if (c.settings.all_topology)
        {
            // Every undirected edge (p, q), p <= q, is found once from its smaller point p
            // by walking p's faces; an edge is a boundary edge when any boundary face uses it.
            const CompactList& pf = c.point_faces();
            const Index n_points = mesh.n_points();
            const Index n_int_faces = mesh.n_internal_faces();
            std::int64_t n_edges = 0, n_internal_edges = 0, n_one = 0, n_two = 0;
#pragma omp parallel if (mesh.n_faces() > detail::parallel_threshold) \
    reduction(+ : n_edges, n_internal_edges, n_one, n_two)
            {
                // mark[q] == p: edge (p, q) already seen; slot[q] its index in `is_boundary`.
                std::vector<Index> mark(static_cast<std::size_t>(n_points), -1);
                std::vector<Index> slot(static_cast<std::size_t>(n_points), 0);
                std::vector<char> is_boundary;
                std::vector<Index> others;
#pragma omp for schedule(static)
                for (Index p = 0; p < n_points; ++p)
                {
                    is_boundary.clear();
                    others.clear();
                    const std::span<const Index> faces_of_p = pf[p];
                    for (std::size_t k = 0; k < faces_of_p.size(); ++k)
                    {
                        const Index f = faces_of_p[k];
                        if (k > 0 && faces_of_p[k - 1] == f)
                            continue; // p repeated in f: all its occurrences seen below
                        const std::span<const Index> face = mesh.faces[f];
                        const std::size_t n = face.size();
                        const bool boundary_face = f >= n_int_faces;
                        for (std::size_t i = 0; i < n; ++i)
                        {
                            if (face[i] != p)
                                continue;
                            for (const Index q : {face[(i + 1) % n], face[(i + n - 1) % n]})
                            {
                                if (q < p)
                                    continue;
                                if (mark[q] != p)
                                {
                                    mark[q] = p;
                                    slot[q] = static_cast<Index>(is_boundary.size());
                                    is_boundary.push_back(0);
                                    others.push_back(q);
                                }
                                is_boundary[slot[q]] |= boundary_face;
                            }
                        }
                    }
                    n_edges += static_cast<std::int64_t>(others.size());
                    for (std::size_t k = 0; k < others.size(); ++k)
                    {
                        if (is_boundary[k])
                            continue;
                        ++n_internal_edges;
                        const int nb = boundary[p] + boundary[others[k]];
                        n_one += nb == 1;
                        n_two += nb == 2;
                    }
                }
            }
            out << "    edges:            " << n_edges << "\n"
                << "    internal edges:   " << n_internal_edges << "\n"
                << "    internal edges using one boundary point:   " << n_one << "\n"
                << "    internal edges using two boundary points:  " << n_two << "\n";
        }
    }
    const Index n_cells = mesh.n_cells;
    out << "    faces:            " << mesh.n_faces() << "\n"
        << "    internal faces:   " << mesh.n_internal_faces() << "\n"
        << "    cells:            " << n_cells << "\n"
        << "    faces per cell:   "
        << c.pr.s(double(mesh.n_faces() + mesh.n_internal_faces()) / std::max<Index>(1, n_cells))
        << "\n"
        << "    boundary patches: " << mesh.patches.size() << "\n"
        << "    point zones:      " << mesh.point_zones.size() << "\n"
        << "    face zones:       " << mesh.face_zones.size() << "\n"
        << "    cell zones:       " << mesh.cell_zones.size() << "\n\n";

    const std::vector<CellShape> shapes = classify_cells(mesh, c.cell_faces);
    const CellShapeCounts counts = count_cell_shapes(shapes, c.cell_faces);
    c.report.cell_types = counts;
    out << "Overall number of cells of each type:\n"
        << "    hexahedra:     " << counts.hex << "\n"
        << "    prisms:        " << counts.prism << "\n"
        << "    wedges:        " << counts.wedge << "\n"
        << "    pyramids:      " << counts.pyramid << "\n"
        << "    tet wedges:    " << counts.tet_wedge << "\n"
        << "    tetrahedra:    " << counts.tet << "\n"
        << "    polyhedra:     " << counts.polyhedron << "\n";
    if (counts.polyhedron > 0)
    {
        out << "    Breakdown of polyhedra by number of faces:\n"
            << "        faces   number of cells\n";
        for (const auto& [n_faces, n] : counts.polyhedra_by_faces)
            out << std::setw(13) << std::right << n_faces << "   " << n << "\n";
        c.pr.right_justify = true;
    }
    out << "\n";
    return shapes;
}

void check_topology(Context& c)
{
    const PolyMesh& mesh = c.mesh;
    std::ostringstream& out = c.pr.out;
    const Index n_faces = mesh.n_faces();
    const Index n_int = mesh.n_internal_faces();
    const Index n_cells = mesh.n_cells;
    out << "Checking topology...\n";

    // 1. Boundary definition.
    {
        bool ok = true;
        Index next = n_int;
        for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        {
            const Patch& p = mesh.patches[i];
            if (p.start_face != next)
                ok = false;
            next = p.start_face + p.n_faces;
            for (std::size_t j = 0; j < i; ++j)
                if (mesh.patches[j].name == p.name)
                    ok = false;
        }
        if (next != n_faces)
            ok = false;
        out << (ok ? "    Boundary definition OK.\n" : " ***Boundary definition is in error.\n");
    }
    // 2. Empty patches.
    {
        Index n_empty = 0;
        for (const Patch& p : mesh.patches)
            if (p.type == "empty")
                n_empty += p.n_faces;
        if (n_cells > 0 && n_empty % n_cells != 0)
            out << " ***Total number of faces on empty patches is not divisible by the number "
                   "of cells in the mesh. Hence this mesh is not 1D or 2D.\n";
    }
    // 3. Illegal cells.
    {
        std::vector<Index> illegal;
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            const std::span<const Index> cf = c.cell_faces[cell];
            bool bad = cf.size() <= 3;
            for (Index f : cf)
                bad = bad || f < 0 || f >= n_faces;
            if (bad)
                illegal.push_back(cell);
        }
        if (!illegal.empty())
        {
            out << "    Illegal cells (less than 4 faces or out of range faces) found,  number "
                   "of cells: "
                << illegal.size() << "\n";
            c.fail("illegalCells");
            c.set("illegalCells", MeshSet::Kind::cell, illegal, "illegal cells");
        }
        else
            out << "    Cell to face addressing OK.\n";
    }
    // 4. Unused points.
    {
        std::vector<char> used(static_cast<std::size_t>(mesh.n_points()), 0);
        for (Index p : mesh.faces.values)
            used[p] = 1;
        std::vector<Index> unused;
        for (Index p = 0; p < mesh.n_points(); ++p)
            if (!used[p])
                unused.push_back(p);
        if (!unused.empty())
        {
            // Every face has an owner cell, so points unused by faces are exactly the points
            // unused by cells.
            out << " ***Unused points found in the mesh, number unused by faces: " << unused.size()
                << " number unused by cells: " << unused.size() << "\n";
            c.fail("unusedPoints");
            c.set("unusedPoints", MeshSet::Kind::point, unused, "unused points", true);
        }
        else
            out << "    Point usage OK.\n";
    }
    // 5. Upper-triangular order.
    {
        bool error = false;
        std::vector<Index> bad;
        for (Index f = 0; f < n_int; ++f)
            if (mesh.owner[f] >= mesh.neighbour[f])
            {
                error = true;
                bad.push_back(f);
            }
        Index n_multiple = 0;
        std::vector<std::pair<Index, Index>> nbr; // (neighbour cell, face)
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            nbr.clear();
            for (Index f : c.cell_faces[cell])
            {
                if (f >= n_int)
                    continue;
                Index other = mesh.neighbour[f] == cell ? mesh.owner[f] : mesh.neighbour[f];
                if (cell < other)
                    nbr.emplace_back(other, f);
            }
            std::stable_sort(nbr.begin(), nbr.end(),
                             [](const auto& a, const auto& b) { return a.first < b.first; });
            bool multiple = false;
            for (std::size_t i = 1; i < nbr.size(); ++i)
            {
                if (nbr[i].first == nbr[i - 1].first)
                {
                    multiple = true;
                    bad.push_back(nbr[i - 1].second);
                    bad.push_back(nbr[i].second);
                }
                else if (nbr[i].second < nbr[i - 1].second)
                {
                    error = true;
                    bad.push_back(nbr[i].second);
                }
            }
            n_multiple += multiple;
        }
        if (n_multiple > 0)
            out << "  <<Found " << n_multiple
                << " neighbouring cells with multiple inbetween faces.\n";
        if (error)
        {
            out << " ***Faces not in upper triangular order.\n";
            c.fail("upperTriangular");
        }
        else
            out << "    Upper triangular ordering OK.\n";
        c.set("upperTriangularFace", MeshSet::Kind::face, bad, "unordered faces");
    }
    // 6. Face vertices (out-of-range labels are rejected before; duplicates counted here).
    {
        Index n_error = 0;
        std::vector<Index> bad;
        std::vector<Index> sorted;
        for (Index f = 0; f < n_faces; ++f)
        {
            const std::span<const Index> face = mesh.faces[f];
            // Each repeated vertex counts once per repetition, as OpenFOAM's hash-set insert.
            Index repeats = 0;
            if (face.size() <= 16)
            {
                for (std::size_t i = 1; i < face.size(); ++i)
                    for (std::size_t j = 0; j < i; ++j)
                        if (face[i] == face[j])
                        {
                            ++repeats;
                            break;
                        }
            }
            else
            {
                sorted.assign(face.begin(), face.end());
                std::sort(sorted.begin(), sorted.end());
                for (std::size_t i = 1; i < sorted.size(); ++i)
                    repeats += sorted[i] == sorted[i - 1];
            }
            if (repeats > 0)
            {
                n_error += repeats;
                bad.push_back(f);
            }
        }
        if (n_error > 0)
        {
            out << "    Faces with invalid vertex labels found,  number of faces: " << n_error
                << "\n";
            c.fail("faceVertices");
            c.set("outOfRangeFaces", MeshSet::Kind::face, bad,
                  "faces with out-of-range or duplicate vertices", true);
        }
        else
            out << "    Face vertices OK.\n";
    }
    if (c.settings.all_topology)
    {
        // 7. Cell zip-up: every edge of a cell used by exactly two of its faces.
        std::vector<char> open(static_cast<std::size_t>(n_cells), 0);
        std::vector<char> listed(static_cast<std::size_t>(n_cells), 0);
#pragma omp parallel if (mesh.n_faces() > detail::parallel_threshold)
        {
            // Edge use counts per cell in a small open-addressing hash table (faster than
            // sorting the cell's edges); only the used slots are reset after each cell.
            constexpr std::uint64_t empty = ~std::uint64_t{0}; // no valid packed edge
            std::vector<std::uint64_t> keys;
            std::vector<std::uint32_t> uses;
            std::vector<std::uint32_t> used_slots;
#pragma omp for schedule(dynamic, 2048)
            for (Index cell = 0; cell < n_cells; ++cell)
            {
                std::size_t n_edges = 0;
                for (Index f : c.cell_faces[cell])
                    n_edges += static_cast<std::size_t>(mesh.faces.item_size(f));
                int bits = 4;
                while ((std::size_t{1} << bits) < 2 * n_edges)
                    ++bits;
                const std::size_t capacity = std::size_t{1} << bits;
                if (keys.size() < capacity)
                {
                    keys.resize(capacity, empty);
                    uses.resize(capacity, 0);
                }
                const std::size_t mask = capacity - 1;
                used_slots.clear();
                for (Index f : c.cell_faces[cell])
                {
                    const std::span<const Index> face = mesh.faces[f];
                    for (std::size_t i = 0; i < face.size(); ++i)
                    {
                        const std::uint64_t e = packed_edge(face[i], face[(i + 1) % face.size()]);
                        std::size_t h = (e * 0x9E3779B97F4A7C15ull) >> (64 - bits);
                        while (keys[h] != empty && keys[h] != e)
                            h = (h + 1) & mask;
                        if (keys[h] == empty)
                        {
                            keys[h] = e;
                            used_slots.push_back(static_cast<std::uint32_t>(h));
                        }
                        ++uses[h];
                    }
                }
                for (const std::uint32_t h : used_slots)
                {
                    if (uses[h] == 1)
                        open[cell] = 1;
                    else if (uses[h] != 2)
                        listed[cell] = 1;
                    keys[h] = empty;
                    uses[h] = 0;
                }
            }
        }
        Index n_open = 0;
        std::vector<Index> zip;
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            n_open += open[cell];
            if (open[cell] || listed[cell])
                zip.push_back(cell);
        }
        if (n_open > 0)
        {
            out << " ***Open cells found, number of cells: " << n_open
                << ". This problem may be fixable using the zipUpMesh utility.\n";
            c.fail("cellsZipUp");
            c.set("zipUpCells", MeshSet::Kind::cell, zip, "cells with over used edges", true);
        }
        else
            out << "    Topological cell zip-up check OK.\n";

        // 8. Face-face connectivity.
        const CompactList& point_faces = c.point_faces();
        const std::vector<Index>& pf_offsets = point_faces.offsets;
        const std::vector<Index>& pf_values = point_faces.values;
        std::vector<Index> n_baffle(static_cast<std::size_t>(n_faces), 0);
        std::vector<Index> n_dup(static_cast<std::size_t>(n_faces), 0);
        std::vector<char> order_error(static_cast<std::size_t>(n_faces), 0);
#pragma omp parallel if (mesh.n_faces() > detail::parallel_threshold)
        {
            // For face f: shared[g].count = number of (vertex position i of f, occurrence
            // of g in the point's faces) pairs for every higher face g sharing a vertex with
            // f (what OpenFOAM counts), first/last position i seen; `touched` lists those g.
            // One record per face (a single cache miss per shared face g); count == 0
            // between faces.
            struct Shared
            {
                Index count = 0, first_pos = 0, last_pos = 0;
            };
            std::vector<Shared> shared(static_cast<std::size_t>(n_faces));
            std::vector<Index> touched;
            std::vector<Index> positions;
            // Whether sorted positions in a face of n vertices form one cyclic run.
            // (Positions are in [0, n): cyclic predecessors without integer division.)
            const auto one_run = [](const std::vector<Index>& pos, Index n)
            {
                std::size_t runs = 0;
                for (std::size_t k = 0; k < pos.size(); ++k)
                {
                    const Index prev = pos[k] == 0 ? n - 1 : pos[k] - 1;
                    const Index before = k == 0 ? pos.back() : pos[k - 1];
                    runs += prev != before;
                }
                return runs <= 1;
            };
            // The higher faces of point p: p's faces are stored in ascending order.
            const auto higher_faces = [&](Index p, Index f)
            {
                const Index* begin = pf_values.data() + pf_offsets[p];
                const Index* end = pf_values.data() + pf_offsets[p + 1];
                // Branch-free count of the faces <= f (lists are short: faster than a
                // binary search's mispredicted branches).
                std::ptrdiff_t n_lower = 0;
                for (const Index* k = begin; k != end; ++k)
                    n_lower += *k <= f;
                return std::span<const Index>(begin + n_lower, end);
            };
#pragma omp for schedule(dynamic, 1024)
            for (Index f = 0; f < n_faces; ++f)
            {
                const std::span<const Index> face = mesh.faces[f];
                const Index n_f = static_cast<Index>(face.size());
                // Memory latency dominates here: prefetch the point-face lists of the next
                // face and the list offsets of the one after (no effect on results).
                if (f + 2 < n_faces)
                {
                    for (const Index p : mesh.faces[f + 1])
                        __builtin_prefetch(pf_values.data() + pf_offsets[p]);
                    for (const Index p : mesh.faces[f + 2])
                        __builtin_prefetch(pf_offsets.data() + p);
                }
                touched.clear();
                for (Index i = 0; i < n_f; ++i)
                    for (const Index g : higher_faces(face[i], f))
                    {
                        Shared& sg = shared[g];
                        if (sg.count == 0)
                        {
                            touched.push_back(g);
                            sg.first_pos = i;
                        }
                        ++sg.count;
                        sg.last_pos = i;
                    }
                for (const Index g : touched)
                    __builtin_prefetch(mesh.faces.offsets.data() + g);
                for (const Index g : touched)
                {
                    const Shared sg = shared[g];
                    shared[g].count = 0;
                    const Index n_common = sg.count;
                    const std::span<const Index> other = mesh.faces[g];
                    const Index n_g = static_cast<Index>(other.size());
                    if (n_common == n_g || n_common == n_f)
                    {
                        if (n_g != n_f)
                            ++n_dup[f];
                        else
                            ++n_baffle[f];
                    }
                    else if (n_common >= 2)
                    {
                        // Shared vertices must form one consecutive run on both faces.
                        // Positions in f, ascending (with repeats), as OpenFOAM collects them.
                        positions.clear();
                        if (n_common == 2)
                        {
                            positions.push_back(sg.first_pos);
                            positions.push_back(sg.last_pos);
                        }
                        else
                        {
                            for (Index i = sg.first_pos; i <= sg.last_pos; ++i)
                                for (const Index h : higher_faces(face[i], f))
                                    if (h == g)
                                        positions.push_back(i);
                        }
                        bool ok = one_run(positions, n_f);
                        if (ok)
                        {
                            for (Index& pos : positions)
                            {
                                const Index p = face[pos];
                                for (Index j = 0; j < n_g; ++j)
                                    if (other[j] == p)
                                    {
                                        pos = j;
                                        break;
                                    }
                            }
                            std::sort(positions.begin(), positions.end());
                            ok = one_run(positions, n_g);
                        }
                        if (!ok)
                            order_error[f] = 1;
                    }
                }
            }
        }
        Index baffles = 0, duplicates = 0, order_errors = 0;
        for (Index f = 0; f < n_faces; ++f)
        {
            baffles += n_baffle[f];
            duplicates += n_dup[f];
            order_errors += order_error[f];
        }
        if (baffles > 0)
            out << "    Number of identical duplicate faces (baffle faces): " << baffles << "\n";
        if (duplicates > 0 || order_errors > 0)
        {
            if (duplicates > 0)
                out << "  <<Number of duplicate (not baffle) faces found: " << duplicates
                    << ". This might indicate a problem.\n";
            if (order_errors > 0)
                out << "  <<Number of faces with non-consecutive shared points: " << order_errors
                    << ". This might indicate a problem.\n";
        }
        else
            out << "    Face-face connectivity OK.\n";

        // 9. Cells with few internal faces.
        std::vector<Index> n_internal(static_cast<std::size_t>(n_cells), 0);
        for (Index f = 0; f < n_int; ++f)
        {
            ++n_internal[mesh.owner[f]];
            ++n_internal[mesh.neighbour[f]];
        }
        std::vector<Index> one, two;
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            if (n_internal[cell] <= 1)
                one.push_back(cell);
            else if (n_internal[cell] == 2)
                two.push_back(cell);
        }
        c.set("oneInternalFaceCells", MeshSet::Kind::cell, one,
              "cells with zero or one non-boundary face");
        c.set("twoInternalFacesCells", MeshSet::Kind::cell, two,
              "cells with two non-boundary faces");
    }
    // 10. Regions.
    {
        std::vector<Index> parent(static_cast<std::size_t>(n_cells));
        std::iota(parent.begin(), parent.end(), 0);
        const auto find = [&](Index a)
        {
            while (parent[a] != a)
                a = parent[a] = parent[parent[a]];
            return a;
        };
        for (Index f = 0; f < n_int; ++f)
        {
            const Index a = find(mesh.owner[f]), b = find(mesh.neighbour[f]);
            if (a != b)
                parent[std::max(a, b)] = std::min(a, b);
        }
        Index n_regions = 0;
        for (Index cell = 0; cell < n_cells; ++cell)
            n_regions += find(cell) == cell;
        if (n_regions <= 1)
            out << "    Number of regions: " << n_regions << " (OK).\n";
        else
        {
            out << "   *Number of regions: " << n_regions << "\n"
                << "    The mesh has multiple regions which are not connected by any face.\n";
            // Region sets in checkMesh's order (region 0 holds cell 0, ...).
            std::vector<Index> region_of_root(static_cast<std::size_t>(n_cells), -1);
            std::vector<std::vector<Index>> regions;
            for (Index cell = 0; cell < n_cells; ++cell)
            {
                const Index r = find(cell);
                if (region_of_root[r] < 0)
                {
                    region_of_root[r] = static_cast<Index>(regions.size());
                    regions.emplace_back();
                }
                regions[region_of_root[r]].push_back(cell);
            }
            for (std::size_t i = 0; i < regions.size(); ++i)
            {
                if (c.settings.report_sets)
                    out << "  <<Writing region " << i << " with " << regions[i].size()
                        << " cells to cellSet region" << i << "\n";
                c.report.sets.push_back(
                    {"region" + std::to_string(i), MeshSet::Kind::cell, regions[i]});
            }
        }
    }

    // Patch topology table.
    const bool all_geometry = c.settings.all_geometry;
    out << "\nChecking patch topology for multiply connected surfaces...\n";
    out << "    " << c.pr.w("Patch", 20) << c.pr.w("Faces", 9) << c.pr.w("Points", 9)
        << c.pr.w("Surface topology", 34);
    if (all_geometry)
        out << " Bounding box";
    out << "\n";
    const auto row_out = [&](const std::string& name, const std::vector<Index>& faces)
    {
        const SurfaceTopology t = surface_topology(mesh, faces);
        out << "    " << c.pr.w(name, 20) << c.pr.w(std::to_string(faces.size()), 9)
            << c.pr.w(std::to_string(t.n_points), 9) << c.pr.w(t.type, 34);
        if (all_geometry && t.n_points > 0)
            out << ' ' << c.pr.v(t.bb_min) << " " << c.pr.v(t.bb_max);
        out << "\n";
    };
    for (const Patch& p : mesh.patches)
    {
        std::vector<Index> faces(static_cast<std::size_t>(p.n_faces));
        std::iota(faces.begin(), faces.end(), p.start_face);
        row_out(p.name, faces);
    }
    out << "\nChecking faceZone topology for multiply connected surfaces...\n";
    if (mesh.face_zones.empty())
        out << "    No faceZones found.\n";
    else
    {
        out << "    " << c.pr.w("FaceZone", 20) << c.pr.w("Faces", 9) << c.pr.w("Points", 9)
            << c.pr.w("Surface topology", 34);
        if (all_geometry)
            out << " Bounding box";
        out << "\n";
        for (const Zone& z : mesh.face_zones)
            row_out(z.name, z.labels);
    }
    out << "\nChecking basic cellZone addressing...\n";
    if (mesh.cell_zones.empty())
        out << "    No cellZones found.\n";
    else
    {
        out << "    " << c.pr.w("CellZone", 20) << c.pr.w("Cells", 13) << c.pr.w("Points", 13)
            << c.pr.w("Volume", 13) << "BoundingBox\n";
        std::vector<char> in_zone(static_cast<std::size_t>(mesh.n_points()), 0);
        for (const Zone& z : mesh.cell_zones)
        {
            std::fill(in_zone.begin(), in_zone.end(), 0);
            double volume = 0;
            Index n_points = 0;
            Eigen::Vector3d lo = Eigen::Vector3d::Constant(constants::vgreat);
            Eigen::Vector3d hi = Eigen::Vector3d::Constant(-constants::vgreat);
            for (Index cell : z.labels)
            {
                volume += c.g.cell_volumes[cell];
                for (Index f : c.cell_faces[cell])
                    for (Index p : mesh.faces[f])
                        if (!in_zone[p])
                        {
                            in_zone[p] = 1;
                            ++n_points;
                            lo = lo.cwiseMin(mesh.points.row(p).transpose());
                            hi = hi.cwiseMax(mesh.points.row(p).transpose());
                        }
            }
            out << "    " << c.pr.w(z.name, 19) << ' '
                << c.pr.w(std::to_string(z.labels.size()), 12) << ' '
                << c.pr.w(std::to_string(n_points), 12) << ' ' << c.pr.w(c.pr.s(volume), 12) << ' '
                << c.pr.v(lo) << " " << c.pr.v(hi) << "\n";
        }
    }
    out << "\n";
}

// ---------------------------------------------------------------------------------------
// Geometry

struct FaceValues
{
    std::vector<double> ortho;    // cos(theta); 1 on uncoupled boundary faces
    std::vector<double> skewness; // all faces
};

void check_geometry(Context& c, FaceValues& fv)
{
    const PolyMesh& mesh = c.mesh;
    const MeshGeometry& g = c.g;
    std::ostringstream& out = c.pr.out;
    QualityReport& r = c.report;
    const Index n_faces = mesh.n_faces();
    const Index n_int = mesh.n_internal_faces();
    const Index n_cells = mesh.n_cells;
    const Printer& pr = c.pr;

    out << "Checking geometry...\n";
    FoamVector lo{constants::vgreat, constants::vgreat, constants::vgreat};
    FoamVector hi{-constants::vgreat, -constants::vgreat, -constants::vgreat};
    for (Index p = 0; p < mesh.n_points(); ++p)
    {
        const FoamVector x = row(mesh.points, p);
        lo = {std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
        hi = {std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z)};
    }
    if (mesh.n_points() == 0)
        lo = hi = FoamVector{};
    r.bounding_box_min = {lo.x, lo.y, lo.z};
    r.bounding_box_max = {hi.x, hi.y, hi.z};
    out << "    Overall domain bounding box " << pr.v(lo) << " " << pr.v(hi) << "\n";
    const MeshDirections dirs = mesh_directions(mesh, g.face_areas);
    r.directions = dirs;
    const Eigen::Vector3i valid = (dirs.geometric + Eigen::Vector3i::Ones()) / 2;
    const Eigen::Vector3i sol = (dirs.solution + Eigen::Vector3i::Ones()) / 2;
    out << "    Mesh has " << dirs.n_geometric() << " geometric (non-empty/wedge) directions ("
        << valid[0] << " " << valid[1] << " " << valid[2] << ")\n";
    out << "    Mesh has " << dirs.n_solution() << " solution (non-empty) directions (" << sol[0]
        << " " << sol[1] << " " << sol[2] << ")\n";

    // G0 edge alignment (2D/1D meshes without wedges).
    if (dirs.n_geometric() < 3 && !dirs.has_wedges)
    {
        std::vector<Edge> bad;
        for (Index f = 0; f < n_faces; ++f)
        {
            const std::span<const Index> face = mesh.faces[f];
            for (std::size_t i = 0; i < face.size(); ++i)
            {
                const Index p0 = face[i], p1 = face[(i + 1) % face.size()];
                if (p0 >= p1)
                    continue;
                FoamVector d = row(mesh.points, p1) - row(mesh.points, p0);
                const double m = detail::mag(d);
                if (m <= rootvsmall)
                    continue;
                d /= m;
                int n_empty = 0, n_valid = 0;
                for (int k = 0; k < 3; ++k)
                    if (std::abs(d[k]) > 1e-6)
                        (valid[k] == 0 ? n_empty : n_valid)++;
                if (n_empty > 1 || (n_empty == 1 && n_valid > 0))
                    bad.push_back({p0, p1});
            }
        }
        std::sort(bad.begin(), bad.end());
        bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
        if (!bad.empty())
        {
            out << " ***Number of edges not aligned with or perpendicular to non-empty "
                   "directions: "
                << bad.size() << "\n";
            c.fail("edgeAlignment");
            std::vector<Index> pts;
            for (const Edge& e : bad)
            {
                pts.push_back(e.first);
                pts.push_back(e.second);
            }
            c.set("nonAlignedEdges", MeshSet::Kind::point, pts, "points on non-aligned edges");
        }
        else
            out << "    All edges aligned with or perpendicular to non-empty directions.\n";
    }

    // G1 boundary openness.
    {
        FoamVector sum;
        double sum_mag = 0;
        for (Index f = n_int; f < n_faces; ++f)
        {
            const FoamVector a = row(g.face_areas, f);
            sum += a;
            sum_mag += detail::mag(a);
        }
        const FoamVector o = sum / (sum_mag + vsmall);
        r.boundary_openness = {o.x, o.y, o.z};
        if (std::max({std::abs(o.x), std::abs(o.y), std::abs(o.z)}) > 1e-6)
        {
            out << " ***Boundary openness " << pr.v(o)
                << " possible hole in boundary description.\n";
            c.fail("boundaryOpenness");
        }
        else
            out << "    Boundary openness " << pr.v(o) << " OK.\n";
    }

    // G2 cell openness and aspect ratio.
    {
        std::vector<double> openness(static_cast<std::size_t>(n_cells));
        r.cell_aspect_ratio.resize(n_cells);
        int n_dims = 0;
        for (int k = 0; k < 3; ++k)
            n_dims += dirs.geometric[k] == 1;
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            FoamVector sum, sum_mag;
            for (Index f : c.cell_faces[cell])
            {
                const FoamVector a = row(g.face_areas, f);
                if (mesh.owner[f] == cell)
                    sum += a;
                else
                    sum -= a;
                sum_mag += detail::cmpt_mag(a);
            }
            double max_open = 0;
            for (int k = 0; k < 3; ++k)
                max_open = std::max(max_open, std::abs(sum[k]) / (sum_mag[k] + rootvsmall));
            openness[cell] = max_open;
            double min_c = constants::vgreat, max_c = -constants::vgreat;
            for (int k = 0; k < 3; ++k)
                if (dirs.geometric[k] == 1)
                {
                    min_c = std::min(min_c, sum_mag[k]);
                    max_c = std::max(max_c, sum_mag[k]);
                }
            double ar = max_c / (min_c + rootvsmall);
            if (n_dims == 3)
            {
                const double v = std::max(rootvsmall, g.cell_volumes[cell]);
                ar = std::max(ar, 1.0 / 6.0 * (sum_mag.x + sum_mag.y + sum_mag.z) /
                                      std::pow(v, 2.0 / 3.0));
            }
            r.cell_aspect_ratio[cell] = ar;
        }
        double max_open = n_cells > 0 ? openness[0] : 0;
        double max_ar = n_cells > 0 ? r.cell_aspect_ratio[0] : 0;
        std::vector<Index> open_cells, aspect_cells;
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            max_open = std::max(max_open, openness[cell]);
            max_ar = std::max(max_ar, r.cell_aspect_ratio[cell]);
            if (openness[cell] > 1e-6)
                open_cells.push_back(cell);
            if (r.cell_aspect_ratio[cell] > 1000)
                aspect_cells.push_back(cell);
        }
        r.max_cell_openness = max_open;
        r.max_aspect_ratio = max_ar;
        r.open_cells = static_cast<Index>(open_cells.size());
        r.high_aspect_ratio_cells = static_cast<Index>(aspect_cells.size());
        if (!open_cells.empty())
        {
            out << " ***Open cells found, max cell openness: " << pr.s(max_open)
                << ", number of open cells " << open_cells.size() << "\n";
            c.fail("cellOpenness");
            c.set("nonClosedCells", MeshSet::Kind::cell, open_cells, "non closed cells");
        }
        else if (!aspect_cells.empty())
        {
            out << " ***High aspect ratio cells found, Max aspect ratio: " << pr.s(max_ar)
                << ", number of cells " << aspect_cells.size() << "\n";
            c.fail("aspectRatio");
        }
        else
            out << "    Max cell openness = " << pr.s(max_open) << " OK.\n"
                << "    Max aspect ratio = " << pr.s(max_ar) << " OK.\n";
        c.set("highAspectRatioCells", MeshSet::Kind::cell, aspect_cells,
              "cells with high aspect ratio");
    }

    // G3 face areas.
    std::vector<double> mag_area(static_cast<std::size_t>(n_faces));
    {
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index f = 0; f < n_faces; ++f)
            mag_area[f] = detail::mag(row(g.face_areas, f));
        double lo_a = great, hi_a = -great;
        std::vector<Index> zero;
        for (Index f = 0; f < n_faces; ++f)
        {
            if (mag_area[f] < vsmall)
                zero.push_back(f);
            lo_a = std::min(lo_a, mag_area[f]);
            hi_a = std::max(hi_a, mag_area[f]);
        }
        r.min_face_area = lo_a;
        r.max_face_area = hi_a;
        if (lo_a < vsmall)
        {
            out << " ***Zero or negative face area detected.  Minimum area: " << pr.s(lo_a) << "\n";
            c.fail("faceAreas");
            c.set("zeroAreaFaces", MeshSet::Kind::face, zero, "zero area faces");
        }
        else
            out << "    Minimum face area = " << pr.s(lo_a)
                << ". Maximum face area = " << pr.s(hi_a) << ".  Face area magnitudes OK.\n";
    }

    // G4 cell volumes.
    {
        double lo_v = great, hi_v = -great, total = 0;
        std::vector<Index> negative;
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            const double v = g.cell_volumes[cell];
            if (v < vsmall)
                negative.push_back(cell);
            lo_v = std::min(lo_v, v);
            hi_v = std::max(hi_v, v);
            total += v;
        }
        r.min_volume = lo_v;
        r.max_volume = hi_v;
        r.total_volume = total;
        r.negative_volume_cells = static_cast<Index>(negative.size());
        if (lo_v < vsmall)
        {
            out << " ***Zero or negative cell volume detected.  Minimum negative volume: "
                << pr.s(lo_v) << ", Number of negative volume cells: " << negative.size() << "\n";
            c.fail("cellVolumes");
            c.set("zeroVolumeCells", MeshSet::Kind::cell, negative, "zero volume cells");
        }
        else
            out << "    Min volume = " << pr.s(lo_v) << ". Max volume = " << pr.s(hi_v)
                << ".  Total volume = " << pr.s(total) << ".  Cell volumes OK.\n";
    }

    // G5 non-orthogonality.
    fv.ortho.assign(static_cast<std::size_t>(n_faces), 1.0);
    {
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index f = 0; f < n_int; ++f)
        {
            const FoamVector d =
                row(g.cell_centres, mesh.neighbour[f]) - row(g.cell_centres, mesh.owner[f]);
            const FoamVector s = row(g.face_areas, f);
            fv.ortho[f] = detail::dot(d, s) / (detail::mag(d) * detail::mag(s) + rootvsmall);
        }
        const double threshold = std::cos(detail::deg_to_rad(70.0));
        double min_cos = great, sum_cos = 0;
        Index n_summed = 0, severe = 0, errors = 0;
        std::vector<Index> faces;
        for (Index f = 0; f < n_faces; ++f)
        {
            const double o = fv.ortho[f];
            if (o < threshold)
            {
                faces.push_back(f);
                if (o > small)
                    ++severe;
                else
                    ++errors;
            }
            if (f < n_int)
            {
                min_cos = std::min(min_cos, o);
                sum_cos += o;
                ++n_summed;
            }
        }
        r.severely_non_orthogonal_faces = severe;
        r.non_orthogonality_errors = errors;
        if (n_summed > 0)
        {
            r.max_non_orthogonality =
                detail::rad_to_deg(std::acos(std::min(1.0, std::max(-1.0, min_cos))));
            r.avg_non_orthogonality =
                detail::rad_to_deg(std::acos(std::min(1.0, std::max(-1.0, sum_cos / n_summed))));
            out << "    Mesh non-orthogonality Max: " << pr.s(r.max_non_orthogonality)
                << " average: " << pr.s(r.avg_non_orthogonality) << "\n";
        }
        if (severe > 0)
            out << "   *Number of severely non-orthogonal (> 70 degrees) faces: " << severe
                << ".\n";
        if (errors > 0)
        {
            out << " ***Number of non-orthogonality errors: " << errors << ".\n";
            c.fail("nonOrthogonality");
        }
        else
            out << "    Non-orthogonality check OK.\n";
        c.set("nonOrthoFaces", MeshSet::Kind::face, faces, "non-orthogonal faces");
    }

    // G6 face pyramids.
    {
        const std::vector<char> n_err = face_pyramid_errors(mesh, g);
        Index errors = 0;
        std::vector<Index> faces;
        for (Index f = 0; f < n_faces; ++f)
            if (n_err[f])
            {
                errors += n_err[f];
                faces.push_back(f);
            }
        r.incorrectly_oriented_face_pyramids = errors;
        if (errors > 0)
        {
            out << " ***Error in face pyramids: " << errors << " faces are incorrectly oriented.\n";
            c.fail("facePyramids");
            c.set("wrongOrientedFaces", MeshSet::Kind::face, faces,
                  "faces with incorrect orientation");
        }
        else
            out << "    Face pyramids OK.\n";
    }

    // G7 skewness.
    fv.skewness.assign(static_cast<std::size_t>(n_faces), 0.0);
    {
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index f = 0; f < n_faces; ++f)
        {
            const FoamVector cf = row(g.face_centres, f);
            const FoamVector af = row(g.face_areas, f);
            const FoamVector own_cc = row(g.cell_centres, mesh.owner[f]);
            const FoamVector cpf = cf - own_cc;
            FoamVector d;
            double factor;
            if (f < n_int)
            {
                d = row(g.cell_centres, mesh.neighbour[f]) - own_cc;
                factor = 0.2;
            }
            else
            {
                FoamVector normal = af;
                normal /= detail::mag(normal) + rootvsmall;
                d = detail::dot(normal, cpf) * normal;
                factor = 0.4;
            }
            const FoamVector sv =
                cpf - (detail::dot(af, cpf) / (detail::dot(af, d) + rootvsmall)) * d;
            const FoamVector sv_hat = sv / (detail::mag(sv) + rootvsmall);
            double fd = factor * detail::mag(d) + rootvsmall;
            for (Index p : mesh.faces[f])
                fd = std::max(fd, std::abs(detail::dot(sv_hat, row(mesh.points, p) - cf)));
            fv.skewness[f] = detail::mag(sv) / fd;
        }
        double max_skew = n_faces > 0 ? fv.skewness[0] : 0;
        std::vector<Index> faces;
        for (Index f = 0; f < n_faces; ++f)
        {
            max_skew = std::max(max_skew, fv.skewness[f]);
            if (fv.skewness[f] > 4)
                faces.push_back(f);
        }
        r.max_skewness = max_skew;
        r.highly_skewed_faces = static_cast<Index>(faces.size());
        if (!faces.empty())
        {
            out << " ***Max skewness = " << pr.s(max_skew) << ", " << faces.size()
                << " highly skew faces detected which may impair the quality of the results\n";
            c.fail("skewness");
            c.set("skewFaces", MeshSet::Kind::face, faces, "skew faces");
        }
        else
            out << "    Max skewness = " << pr.s(max_skew) << " OK.\n";
    }

    // G8 coupled points (no coupled patches are treated as coupled).
    out << "    Coupled point location match (average 0) OK.\n";

    // Per-cell maxima for VTK fields.
    r.cell_non_orthogonality = Eigen::VectorXd::Zero(n_cells);
    r.cell_skewness = Eigen::VectorXd::Zero(n_cells);
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
    for (Index cell = 0; cell < n_cells; ++cell)
    {
        double min_cos = 1, max_skew = 0;
        for (Index f : c.cell_faces[cell])
        {
            min_cos = std::min(min_cos, fv.ortho[f]);
            max_skew = std::max(max_skew, fv.skewness[f]);
        }
        r.cell_non_orthogonality[cell] =
            detail::rad_to_deg(std::acos(std::min(1.0, std::max(-1.0, min_cos))));
        r.cell_skewness[cell] = max_skew;
    }

    // Cell determinants (A5) are always computed: they are a VTK field.
    {
        r.cell_determinant.resize(n_cells);
        int n_dims = dirs.n_geometric();
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            if (n_dims == 1)
            {
                r.cell_determinant[cell] = 1.0;
                continue;
            }
            double avg = 0;
            Index n_internal = 0;
            for (Index f : c.cell_faces[cell])
                if (f < n_int)
                {
                    avg += mag_area[f];
                    ++n_internal;
                }
            if (n_internal == 0 || avg < rootvsmall)
            {
                r.cell_determinant[cell] = 0;
                continue;
            }
            avg /= static_cast<double>(n_internal);
            double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
            for (Index f : c.cell_faces[cell])
                if (f < n_int)
                {
                    const FoamVector a = row(g.face_areas, f) / avg;
                    xx += a.x * a.x;
                    xy += a.x * a.y;
                    xz += a.x * a.z;
                    yy += a.y * a.y;
                    yz += a.y * a.z;
                    zz += a.z * a.z;
                }
            if (n_dims == 2)
            {
                if (dirs.geometric[0] == -1)
                    xx = 1;
                if (dirs.geometric[1] == -1)
                    yy = 1;
                if (dirs.geometric[2] == -1)
                    zz = 1;
            }
            const double det = xx * yy * zz + xy * yz * xz + xz * xy * yz - xx * yz * yz -
                               xy * xy * zz - xz * yy * xz;
            r.cell_determinant[cell] = std::abs(det) / 8.0;
        }
    }

    if (!c.settings.all_geometry)
        return;
    r.has_all_geometry = true;

    // A1 face tets.
    {
        constexpr double tol = small * small;
        std::vector<char> n_err(static_cast<std::size_t>(n_faces), 0);
#pragma omp parallel for schedule(dynamic, 4096) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index f = 0; f < n_faces; ++f)
        {
            const std::span<const Index> face = mesh.faces[f];
            const std::size_t n = face.size();
            const FoamVector cf = row(g.face_centres, f);
            const FoamVector co = row(g.cell_centres, mesh.owner[f]);
            const bool internal = f < n_int;
            const FoamVector cn = internal ? row(g.cell_centres, mesh.neighbour[f]) : co;
            char errors = 0;
            for (std::size_t i = 0; i < n; ++i)
                if (detail::tet_quality(row(mesh.points, face[i]),
                                        row(mesh.points, face[(i + 1) % n]), cf, co) > -tol)
                {
                    ++errors;
                    break;
                }
            if (internal)
                for (std::size_t i = 0; i < n; ++i)
                    if (detail::tet_quality(row(mesh.points, face[i]),
                                            row(mesh.points, face[(i + 1) % n]), cf, cn) < tol)
                    {
                        ++errors;
                        break;
                    }
            bool found_base = false;
            for (std::size_t b = 0; b < n && !found_base; ++b)
            {
                const FoamVector pb = row(mesh.points, face[b]);
                double min_q = constants::vgreat;
                for (std::size_t t = 1; t + 1 < n; ++t)
                {
                    const std::size_t i = (b + t) % n, j = (i + 1) % n;
                    const FoamVector pi = row(mesh.points, face[i]);
                    const FoamVector pj = row(mesh.points, face[j]);
                    double q = detail::tet_quality(co, pb, pi, pj);
                    if (internal)
                        q = std::min(q, detail::tet_quality(cn, pb, pj, pi));
                    min_q = std::min(min_q, q);
                }
                found_base = min_q > tol;
            }
            if (!found_base)
                ++errors;
            n_err[f] = errors;
        }
        Index errors = 0;
        std::vector<Index> faces;
        for (Index f = 0; f < n_faces; ++f)
            if (n_err[f])
            {
                errors += n_err[f];
                faces.push_back(f);
            }
        r.face_tet_errors = errors;
        if (errors > 0)
        {
            out << " ***Error in face tets: " << errors
                << " faces with low quality or negative volume decomposition tets.\n";
            c.fail("faceTets");
            c.set("lowQualityTetFaces", MeshSet::Kind::face, faces,
                  "faces with low quality or negative volume decomposition tets");
        }
        else
            out << "    Face tets OK.\n";
    }

    // A2 edge length.
    {
        const FoamVector span = hi - lo;
        const double min_dist_sqr = detail::mag_sqr(1e-6 * span);
        double min_len = great * great, max_len = -great * great;
        std::vector<char> marked(static_cast<std::size_t>(mesh.n_points()), 0);
        Index n_small = 0;
        for (Index f = 0; f < n_faces; ++f)
        {
            const std::span<const Index> face = mesh.faces[f];
            for (std::size_t i = 0; i < face.size(); ++i)
            {
                const Index a = face[i], b = face[(i + 1) % face.size()];
                const double len = detail::mag_sqr(row(mesh.points, a) - row(mesh.points, b));
                if (len < min_dist_sqr)
                {
                    // OpenFOAM: if (set.insert(a) || set.insert(b)) nSmall++ (short-circuit).
                    if (!marked[a])
                    {
                        marked[a] = 1;
                        ++n_small;
                    }
                    else if (!marked[b])
                    {
                        marked[b] = 1;
                        ++n_small;
                    }
                }
                min_len = std::min(min_len, len);
                max_len = std::max(max_len, len);
            }
        }
        r.min_edge_length = std::sqrt(min_len);
        r.max_edge_length = std::sqrt(max_len);
        r.short_edges = n_small;
        if (n_small > 0)
        {
            out << "   *Edges too small, min/max edge length = " << pr.s(r.min_edge_length) << " "
                << pr.s(r.max_edge_length) << ", number too small: " << n_small << "\n";
            c.set("shortEdges", MeshSet::Kind::point, flagged(marked), "points on short edges");
        }
        else
            out << "    Min/max edge length = " << pr.s(r.min_edge_length) << " "
                << pr.s(r.max_edge_length) << " OK.\n";
    }

    // A3 concave faces.
    {
        const double max_sin = std::sin(detail::deg_to_rad(10.0));
        std::vector<double> concavity(static_cast<std::size_t>(n_faces), 0.0);
#pragma omp parallel for schedule(dynamic, 4096) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index f = 0; f < n_faces; ++f)
        {
            const std::span<const Index> face = mesh.faces[f];
            if (face.empty())
                continue;
            FoamVector normal = row(g.face_areas, f);
            normal /= detail::mag(normal) + rootvsmall;
            const std::size_t n = face.size();
            // Corner i between the raw edges E_prev = p[i] - p[i-1] and E = p[i+1] - p[i].
            FoamVector raw_prev = row(mesh.points, face.front()) - row(mesh.points, face.back());
            double max_edge_sin = 0;
            for (std::size_t i = 0; i < n; ++i)
            {
                const FoamVector raw =
                    row(mesh.points, face[(i + 1) % n]) - row(mesh.points, face[i]);
                // Shortcut (no sqrt/division): (E_prev ^ E) & normal > |E_prev ^ E| / 2 (with
                // margin) is a convex corner: checkMesh's normalised w = e_prev ^ e is the
                // same vector scaled by a positive factor, so (w/|w|) & normal > 1/2 up to
                // rounding (~1e-14 when |w| >= sin 10 deg, |normal| <= 1), far above `small`:
                // never counted. Every other corner takes checkMesh's exact path below.
                const FoamVector w_raw = detail::cross(raw_prev, raw);
                const double d_raw = detail::dot(w_raw, normal);
                if (!(d_raw > 0 && d_raw * d_raw > 0.25 * (1 + 1e-9) * detail::mag_sqr(w_raw)))
                {
                    const double mag_prev = detail::mag(raw_prev);
                    const FoamVector e_prev = raw_prev / (mag_prev + rootvsmall);
                    const double mag_e = detail::mag(raw);
                    const FoamVector e = raw / (mag_e + rootvsmall);
                    if (mag_prev > small && mag_e > small)
                    {
                        FoamVector w = detail::cross(e_prev, e);
                        const double mag_w = detail::mag(w);
                        if (mag_w >= max_sin)
                        {
                            w /= mag_w;
                            if (detail::dot(w, normal) < small)
                                max_edge_sin = std::max(max_edge_sin, mag_w);
                        }
                    }
                }
                raw_prev = raw;
            }
            concavity[f] = max_edge_sin;
        }
        double max_s = 0;
        std::vector<Index> faces;
        for (Index f = 0; f < n_faces; ++f)
        {
            max_s = std::max(max_s, concavity[f]);
            if (concavity[f] > small)
                faces.push_back(f);
        }
        r.concave_faces = static_cast<Index>(faces.size());
        r.max_concave_angle = detail::rad_to_deg(std::asin(std::min(1.0, max_s)));
        if (!faces.empty())
        {
            out << "   *There are " << faces.size()
                << " faces with concave angles between consecutive edges. Max concave angle = "
                << pr.s(r.max_concave_angle) << " degrees.\n";
            c.set("concaveFaces", MeshSet::Kind::face, faces, "faces with concave angles");
        }
        else
            out << "    All angles in faces OK.\n";
    }

    // A4 flatness.
    {
        std::vector<double> flatness(static_cast<std::size_t>(n_faces), 1.0);
#pragma omp parallel for schedule(dynamic, 4096) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index f = 0; f < n_faces; ++f)
        {
            const std::span<const Index> face = mesh.faces[f];
            if (face.size() <= 3 || mag_area[f] <= rootvsmall)
                continue;
            const FoamVector fc = row(g.face_centres, f);
            double sum_a = 0;
            for (std::size_t i = 0; i < face.size(); ++i)
            {
                const FoamVector pi = row(mesh.points, face[i]);
                const FoamVector pj = row(mesh.points, face[(i + 1) % face.size()]);
                sum_a += detail::mag(0.5 * detail::cross(pj - pi, fc - pi));
            }
            flatness[f] = mag_area[f] / (sum_a + rootvsmall);
        }
        double min_flat = great, sum_flat = 0;
        Index n_summed = 0;
        std::vector<Index> faces;
        for (Index f = 0; f < n_faces; ++f)
        {
            if (mesh.faces.item_size(f) > 3 && mag_area[f] > vsmall)
            {
                sum_flat += flatness[f];
                ++n_summed;
                min_flat = std::min(min_flat, flatness[f]);
                if (flatness[f] < 0.8)
                    faces.push_back(f);
            }
        }
        r.warped_faces = static_cast<Index>(faces.size());
        if (n_summed > 0)
        {
            r.min_face_flatness = min_flat;
            r.avg_face_flatness = sum_flat / n_summed;
            out << "    Face flatness (1 = flat, 0 = butterfly) : min = " << pr.s(min_flat)
                << "  average = " << pr.s(sum_flat / n_summed) << "\n";
        }
        if (!faces.empty())
        {
            out << "   *There are " << faces.size()
                << " faces with ratio between projected and actual area < 0.8\n"
                << "    Minimum ratio (minimum flatness, maximum warpage) = " << pr.s(min_flat)
                << "\n";
            c.set("warpedFaces", MeshSet::Kind::face, faces, "warped faces");
        }
        else
            out << "    All face flatness OK.\n";
    }

    // A5 cell determinant.
    {
        double min_det = n_cells > 0 ? r.cell_determinant[0] : 0, sum_det = 0;
        std::vector<Index> cells;
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            min_det = std::min(min_det, r.cell_determinant[cell]);
            sum_det += r.cell_determinant[cell];
            if (r.cell_determinant[cell] < 1e-3)
                cells.push_back(cell);
        }
        r.min_determinant = min_det;
        r.avg_determinant = n_cells > 0 ? sum_det / n_cells : 0;
        r.small_determinant_cells = static_cast<Index>(cells.size());
        if (n_cells > 0)
            out << "    Cell determinant (wellposedness) : minimum: " << pr.s(min_det)
                << " average: " << pr.s(r.avg_determinant) << "\n";
        if (!cells.empty())
        {
            out << " ***Cells with small determinant (< 0.001) found, number of cells: "
                << cells.size() << "\n";
            c.fail("cellDeterminant");
            c.set("underdeterminedCells", MeshSet::Kind::cell, cells, "under-determined cells",
                  true);
        }
        else
            out << "    Cell determinant check OK.\n";
    }

    // A6 concave cells.
    {
        std::vector<char> concave(static_cast<std::size_t>(n_cells), 0);
#pragma omp parallel for schedule(dynamic, 2048) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            const std::span<const Index> cf = c.cell_faces[cell];
            bool is_concave = false;
            for (std::size_t i = 0; i < cf.size() && !is_concave; ++i)
            {
                const Index fi = cf[i];
                const FoamVector ci = row(g.face_centres, fi);
                FoamVector n = row(g.face_areas, fi);
                n /= std::max(detail::mag(n), vsmall);
                if (mesh.owner[fi] != cell)
                    n = -n;
                for (std::size_t j = 0; j < cf.size(); ++j)
                {
                    if (j == i)
                        continue;
                    FoamVector u = row(g.face_centres, cf[j]) - ci;
                    // Shortcut (no sqrt/divisions): when (u & n) / |u| < -2e-6 exactly,
                    // the rounded normalised product checkMesh computes (error ~1e-15, as
                    // |u/|u|| = 1 and |n| <= 1) is certainly below -1e-6, so the pair
                    // passes. Only for |u|^2 well above vsmall^2 and without underflow of
                    // s^2; every other pair takes OpenFOAM's exact path below.
                    const double s_un = detail::dot(u, n);
                    const double m2 = detail::mag_sqr(u);
                    if (s_un < 0 && m2 > 1e-200 && s_un * s_un > 4e-12 * m2)
                        continue;
                    u /= std::max(detail::mag(u), vsmall);
                    if (detail::dot(u, n) > -1e-6)
                    {
                        is_concave = true;
                        break;
                    }
                }
            }
            concave[cell] = is_concave;
        }
        const std::vector<Index> cells = flagged(concave);
        r.concave_cells = static_cast<Index>(cells.size());
        if (!cells.empty())
        {
            out << " ***Concave cells (using face planes) found, number of cells: " << cells.size()
                << "\n";
            c.fail("concaveCells");
            c.set("concaveCells", MeshSet::Kind::cell, cells, "concave cells", true);
        }
        else
            out << "    Concave cell check OK.\n";
    }

    // A7 face weights.
    {
        std::vector<double> weight(static_cast<std::size_t>(n_int));
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index f = 0; f < n_int; ++f)
        {
            const FoamVector fc = row(g.face_centres, f);
            const FoamVector fa = row(g.face_areas, f);
            const double d_own = std::abs(detail::dot(fa, fc - row(g.cell_centres, mesh.owner[f])));
            const double d_nei =
                std::abs(detail::dot(fa, row(g.cell_centres, mesh.neighbour[f]) - fc));
            weight[f] = std::min(d_nei, d_own) / (d_nei + d_own + vsmall);
        }
        double min_w = great, sum_w = 0;
        std::vector<Index> faces;
        for (Index f = 0; f < n_int; ++f)
        {
            if (weight[f] < 0.05)
                faces.push_back(f);
            min_w = std::min(min_w, weight[f]);
            sum_w += weight[f];
        }
        r.low_weight_faces = static_cast<Index>(faces.size());
        if (n_int > 0)
        {
            r.min_face_weight = min_w;
            r.avg_face_weight = sum_w / n_int;
            out << "    Face interpolation weight : minimum: " << pr.s(min_w)
                << " average: " << pr.s(r.avg_face_weight) << "\n";
        }
        if (!faces.empty())
        {
            out << " ***Faces with small interpolation weight (< 0.05) found, number of faces: "
                << faces.size() << "\n";
            c.fail("faceWeight");
            c.set("lowWeightFaces", MeshSet::Kind::face, faces,
                  "faces with low interpolation weights", true);
        }
        else
            out << "    Face interpolation weight check OK.\n";
    }

    // A8 volume ratio.
    {
        double min_r = great, sum_r = 0;
        std::vector<Index> faces;
        for (Index f = 0; f < n_int; ++f)
        {
            const double vo = g.cell_volumes[mesh.owner[f]];
            const double vn = g.cell_volumes[mesh.neighbour[f]];
            const double ratio = std::min(vo, vn) / (std::max(vo, vn) + vsmall);
            if (ratio < 0.01)
                faces.push_back(f);
            min_r = std::min(min_r, ratio);
            sum_r += ratio;
        }
        r.low_volume_ratio_faces = static_cast<Index>(faces.size());
        if (n_int > 0)
        {
            r.min_volume_ratio = min_r;
            r.avg_volume_ratio = sum_r / n_int;
            out << "    Face volume ratio : minimum: " << pr.s(min_r)
                << " average: " << pr.s(r.avg_volume_ratio) << "\n";
        }
        if (!faces.empty())
        {
            out << " ***Faces with small volume ratio (< 0.01) found, number of faces: "
                << faces.size() << "\n";
            c.fail("volumeRatio");
            c.set("lowVolRatioFaces", MeshSet::Kind::face, faces,
                  "faces with low volume ratio cells", true);
        }
        else
            out << "    Face volume ratio check OK.\n";
    }
}

void validate(const PolyMesh& mesh)
{
    const Index n_points = mesh.n_points();
    for (Index f = 0; f < mesh.n_faces(); ++f)
        for (Index p : mesh.faces[f])
            if (p < 0 || p >= n_points)
                throw InvalidInput("face " + std::to_string(f) + " has vertex label " +
                                   std::to_string(p) + " outside [0, " + std::to_string(n_points) +
                                   ")");
    if (static_cast<Index>(mesh.owner.size()) != mesh.n_faces())
        throw InvalidInput("owner has " + std::to_string(mesh.owner.size()) + " entries for " +
                           std::to_string(mesh.n_faces()) + " faces");
    if (mesh.n_internal_faces() > mesh.n_faces())
        throw InvalidInput("more neighbour entries than faces");
    for (Index cell : mesh.owner)
        if (cell < 0 || cell >= mesh.n_cells)
            throw InvalidInput("owner label " + std::to_string(cell) + " outside [0, nCells)");
    for (Index cell : mesh.neighbour)
        if (cell < 0 || cell >= mesh.n_cells)
            throw InvalidInput("neighbour label " + std::to_string(cell) + " outside [0, nCells)");
}

} // namespace

void check_mesh_quality_dict(const PolyMesh& mesh, const CompactList& cell_faces,
                             const MeshGeometry& geometry, const MeshQualitySettings& q,
                             int precision, bool right_justify, std::ostringstream& out,
                             QualityReport& report, const std::vector<double>& skewness);

QualityReport check_mesh(const PolyMesh& mesh, const CompactList& cell_faces,
                         const MeshGeometry& geometry, const CheckMeshSettings& settings)
{
    validate(mesh);
    if (cell_faces.size() != mesh.n_cells)
        throw InvalidInput("cell_faces has " + std::to_string(cell_faces.size()) +
                           " cells, the mesh " + std::to_string(mesh.n_cells));
    QualityReport report;
    report.n_points = mesh.n_points();
    report.n_faces = mesh.n_faces();
    report.n_internal_faces = mesh.n_internal_faces();
    report.n_cells = mesh.n_cells;
    report.n_patches = static_cast<Index>(mesh.patches.size());
    Printer printer(settings.write_precision);
    Context context{mesh, cell_faces, geometry, settings, report, printer, {}};
    const std::vector<CellShape> shapes = mesh_stats(context);
    // The paper's measure (not a checkMesh check): minimum over cells where it is defined.
    if (settings.scaled_jacobian)
        report.cell_scaled_jacobian = scaled_jacobian(mesh, cell_faces, shapes);
    for (Index cell = 0; cell < report.cell_scaled_jacobian.size(); ++cell)
    {
        const double sj = report.cell_scaled_jacobian[cell];
        if (std::isfinite(sj) &&
            !(std::isfinite(report.min_scaled_jacobian) && report.min_scaled_jacobian <= sj))
            report.min_scaled_jacobian = sj;
    }
    if (!settings.no_topology)
        check_topology(context);
    FaceValues fv;
    check_geometry(context, fv);
    if (settings.mesh_quality)
    {
        report.has_mesh_quality = true;
        check_mesh_quality_dict(mesh, cell_faces, geometry, *settings.mesh_quality,
                                settings.write_precision, printer.right_justify, printer.out,
                                report, fv.skewness);
        if (report.mesh_quality_faces > 0)
        {
            context.fail("meshQuality");
            if (settings.report_sets)
                printer.out << "  <<Writing " << report.mesh_quality_faces
                            << " faces in error to set meshQualityFaces\n";
        }
    }
    if (report.failed_checks == 0)
        printer.out << "\nMesh OK.\n";
    else
        printer.out << "\nFailed " << report.failed_checks << " mesh checks.\n";
    report.text = printer.out.str();
    return report;
}

QualityReport check_mesh(const PolyMesh& mesh, const CheckMeshSettings& settings)
{
    validate(mesh);
    const CompactList cf = cell_faces(mesh);
    const MeshGeometry geometry = compute_geometry(mesh, cf);
    return check_mesh(mesh, cf, geometry, settings);
}

} // namespace meshmorph
