// SPDX-License-Identifier: GPL-3.0-or-later
// Cell shape matching after OpenFOAM's cellMatcher family, and VTK connectivity.
#include "meshmorph/core/cell_shapes.h"

#include <algorithm>
#include <array>
#include <string>

#include "meshmorph/core/exceptions.h"

namespace meshmorph
{
namespace
{

// The largest models matched here: hex (8 vertices, 6 faces, quads).
constexpr int max_vert = 8;
constexpr int max_face = 6;
constexpr int max_face_size = 4;

// The shape of one cell in cell-local numbering, with OpenFOAM's cellMatcher addressing:
// localFaces_, faceSize_, pointMap_, faceMap_, edgeFaces_ and pointFaceIndex_. Every walk
// below mirrors the corresponding OpenFOAM matcher step by step, because which cells checkMesh
// accepts depends on the exact walk (first triangle, vertex 0, orientation by owner).
class LocalCell
{
public:
    LocalCell(const PolyMesh& mesh, std::span<const Index> faces, Index cell)
        : mesh_(mesh), faces_(faces), cell_(cell)
    {
    }

    // cellMatcher::calcLocalFaces, then calcEdgeAddressing and calcPointFaceIndex. Returns
    // false where OpenFOAM returns a vertex count other than vert_per_cell, and where its
    // calcEdgeAddressing aborts (an edge used by more than two faces of the cell).
    // Cells with more than max_face faces or faces above max_face_size vertices never match.
    bool prepare(int vert_per_cell)
    {
        if (faces_.size() > static_cast<std::size_t>(max_face))
            return false;
        n_faces_ = static_cast<int>(faces_.size());
        num_vert_ = 0;
        for (int lf = 0; lf < n_faces_; ++lf)
        {
            const std::span<const Index> f = mesh_.faces[faces_[lf]];
            if (f.size() > static_cast<std::size_t>(max_face_size))
                return false;
            face_size_[lf] = static_cast<int>(f.size());
            for (int fp = 0; fp < face_size_[lf]; ++fp)
            {
                const Index* found =
                    std::find(point_map_.data(), point_map_.data() + num_vert_, f[fp]);
                int local = static_cast<int>(found - point_map_.data());
                if (local == num_vert_)
                {
                    if (num_vert_ >= vert_per_cell)
                        return false; // more distinct vertices than the model has
                    point_map_[num_vert_++] = f[fp];
                }
                local_faces_[lf][fp] = local;
            }
        }
        if (num_vert_ != vert_per_cell)
            return false;

        edge_faces_.fill(-1);
        for (int lf = 0; lf < n_faces_; ++lf)
        {
            int prev = face_size_[lf] - 1;
            for (int fp = 0; fp < face_size_[lf]; ++fp)
            {
                const int key1 = edge_key(local_faces_[lf][prev], local_faces_[lf][fp]);
                const int key2 = edge_key(local_faces_[lf][fp], local_faces_[lf][prev]);
                if (edge_faces_[key1] == -1)
                {
                    edge_faces_[key1] = lf;
                    edge_faces_[key2] = lf;
                }
                else if (edge_faces_[key1 + 1] == -1)
                {
                    edge_faces_[key1 + 1] = lf;
                    edge_faces_[key2 + 1] = lf;
                }
                else
                {
                    return false; // OpenFOAM: "edgeFaces_ full" (FatalError)
                }
                prev = fp;
            }
        }

        for (auto& row : point_face_index_)
            row.fill(-1);
        for (int lf = 0; lf < n_faces_; ++lf)
            for (int fp = 0; fp < face_size_[lf]; ++fp)
                point_face_index_[local_faces_[lf][fp]][lf] = fp;
        return true;
    }

    int face_size(int lf) const { return face_size_[lf]; }
    int vertex(int lf, int fp) const { return local_faces_[lf][fp]; }
    Index mesh_point(int local_vertex) const { return point_map_[local_vertex]; }
    // Whether the cell owns local face lf (its vertices then run right-handed outwards).
    bool owns(int lf) const { return mesh_.owner[faces_[lf]] == cell_; }
    // Position of local vertex v in local face lf, or -1.
    int index_in_face(int v, int lf) const { return point_face_index_[v][lf]; }

    // cellMatcher::otherFace: the other face on edge (v0, v1). Returns -1 when the edge has
    // a single face (OpenFOAM reads faceSize_[-1] there) and -2 when lf is not on the edge
    // (OpenFOAM: FatalError).
    int other_face(int v0, int v1, int lf) const
    {
        const int key = edge_key(v0, v1);
        if (edge_faces_[key] == lf)
            return edge_faces_[key + 1];
        if (edge_faces_[key + 1] == lf)
            return edge_faces_[key];
        return -2;
    }

    // cellMatcher::nextVert.
    static int next_vert(int i, int size, bool right_hand)
    {
        return right_hand ? (i + 1) % size : (size + i - 1) % size;
    }

private:
    int edge_key(int v0, int v1) const { return 2 * (v0 * num_vert_ + v1); }

    const PolyMesh& mesh_;
    std::span<const Index> faces_;
    Index cell_;
    int n_faces_ = 0;
    int num_vert_ = 0;
    std::array<std::array<int, max_face_size>, max_face> local_faces_{};
    std::array<int, max_face> face_size_{};
    std::array<Index, max_vert> point_map_{};
    std::array<int, 2 * max_vert * max_vert> edge_faces_{};
    std::array<std::array<int, max_face>, max_vert> point_face_index_{};
};

struct SizeCount
{
    int tris = 0;
    int quads = 0;
    int other = 0;
};

SizeCount count_face_sizes(const PolyMesh& mesh, std::span<const Index> faces)
{
    SizeCount c;
    for (Index f : faces)
    {
        const Index n = mesh.faces.item_size(f);
        if (n == 3)
            ++c.tris;
        else if (n == 4)
            ++c.quads;
        else
            ++c.other;
    }
    return c;
}

bool sizes_are(const SizeCount& c, std::size_t n_faces, int tris, int quads)
{
    return c.other == 0 && c.tris == tris && c.quads == quads &&
           static_cast<std::size_t>(tris + quads) == n_faces;
}

// Vertex labels in OpenFOAM's model order, filled by the full matchers.
using VertLabels = std::array<Index, max_vert>;

// hexMatcher::matchShape(checkOnly = false).
bool match_hex(LocalCell& lc, VertLabels& vert)
{
    if (!lc.prepare(8))
        return false;
    const int f4 = 0;
    const bool r4 = !lc.owns(f4);
    const int f4v0 = 0;
    const int f4v1 = LocalCell::next_vert(f4v0, lc.face_size(f4), r4);
    const int f4v2 = LocalCell::next_vert(f4v1, lc.face_size(f4), r4);
    const int f4v3 = LocalCell::next_vert(f4v2, lc.face_size(f4), r4);
    vert[0] = lc.mesh_point(lc.vertex(f4, f4v0));
    vert[1] = lc.mesh_point(lc.vertex(f4, f4v1));
    vert[2] = lc.mesh_point(lc.vertex(f4, f4v2));
    vert[3] = lc.mesh_point(lc.vertex(f4, f4v3));

    const int f0 = lc.other_face(lc.vertex(f4, f4v3), lc.vertex(f4, f4v0), f4);
    if (f0 < 0)
        return false;
    const int f0v0 = lc.index_in_face(lc.vertex(f4, f4v0), f0);
    if (f0v0 < 0)
        return false;
    const int f0v4 = LocalCell::next_vert(f0v0, lc.face_size(f0), lc.owns(f0));
    const int f0v7 = LocalCell::next_vert(f0v4, lc.face_size(f0), lc.owns(f0));
    vert[4] = lc.mesh_point(lc.vertex(f0, f0v4));
    vert[7] = lc.mesh_point(lc.vertex(f0, f0v7));

    const int f5 = lc.other_face(lc.vertex(f0, f0v4), lc.vertex(f0, f0v7), f0);
    if (f5 < 0)
        return false;
    const int f5v4 = lc.index_in_face(lc.vertex(f0, f0v4), f5);
    if (f5v4 < 0)
        return false;
    const int f5v5 = LocalCell::next_vert(f5v4, lc.face_size(f5), lc.owns(f5));
    const int f5v6 = LocalCell::next_vert(f5v5, lc.face_size(f5), lc.owns(f5));
    vert[5] = lc.mesh_point(lc.vertex(f5, f5v5));
    vert[6] = lc.mesh_point(lc.vertex(f5, f5v6));
    return true;
}

// tetMatcher::matchShape(checkOnly = false).
bool match_tet(LocalCell& lc, VertLabels& vert)
{
    if (!lc.prepare(4))
        return false;
    const int f3 = 0;
    const bool r3 = !lc.owns(f3);
    const int f3v0 = 0;
    const int f3v1 = LocalCell::next_vert(f3v0, lc.face_size(f3), r3);
    const int f3v2 = LocalCell::next_vert(f3v1, lc.face_size(f3), r3);
    vert[0] = lc.mesh_point(lc.vertex(f3, f3v0));
    vert[1] = lc.mesh_point(lc.vertex(f3, f3v1));
    vert[2] = lc.mesh_point(lc.vertex(f3, f3v2));
    const int f1 = lc.other_face(lc.vertex(f3, f3v2), lc.vertex(f3, f3v0), f3);
    if (f1 < 0)
        return false;
    const int f1v0 = lc.index_in_face(lc.vertex(f3, f3v0), f1);
    if (f1v0 < 0)
        return false;
    const int f1v3 = LocalCell::next_vert(f1v0, lc.face_size(f1), lc.owns(f1));
    vert[3] = lc.mesh_point(lc.vertex(f1, f1v3));
    return true;
}

// pyrMatcher::matchShape(checkOnly = false).
bool match_pyramid(LocalCell& lc, VertLabels& vert, int n_faces)
{
    if (!lc.prepare(5))
        return false;
    int f0 = -1;
    for (int lf = 0; lf < n_faces && f0 < 0; ++lf)
        if (lc.face_size(lf) == 4)
            f0 = lf;
    const bool r0 = !lc.owns(f0);
    const int f0v0 = 0;
    const int f0v1 = LocalCell::next_vert(f0v0, 4, r0);
    const int f0v2 = LocalCell::next_vert(f0v1, 4, r0);
    const int f0v3 = LocalCell::next_vert(f0v2, 4, r0);
    vert[0] = lc.mesh_point(lc.vertex(f0, f0v0));
    vert[1] = lc.mesh_point(lc.vertex(f0, f0v1));
    vert[2] = lc.mesh_point(lc.vertex(f0, f0v2));
    vert[3] = lc.mesh_point(lc.vertex(f0, f0v3));
    const int f4 = lc.other_face(lc.vertex(f0, f0v0), lc.vertex(f0, f0v1), f0);
    if (f4 < 0)
        return false;
    const int f4v0 = lc.index_in_face(lc.vertex(f0, f0v0), f4);
    if (f4v0 < 0)
        return false;
    const int f4v4 = LocalCell::next_vert(f4v0, lc.face_size(f4), !lc.owns(f4));
    vert[4] = lc.mesh_point(lc.vertex(f4, f4v4));
    return true;
}

// prismMatcher::matchShape. With check_only it returns where OpenFOAM's isA returns.
bool match_prism(LocalCell& lc, VertLabels& vert, int n_faces, bool check_only)
{
    if (!lc.prepare(6))
        return false;
    int f0 = -1;
    for (int lf = 0; lf < n_faces && f0 < 0; ++lf)
        if (lc.face_size(lf) == 3)
            f0 = lf;
    const bool r0 = !lc.owns(f0);
    const int f0v0 = 0;
    const int f0v1 = LocalCell::next_vert(f0v0, 3, r0);
    vert[0] = lc.mesh_point(lc.vertex(f0, f0v0));
    vert[1] = lc.mesh_point(lc.vertex(f0, f0v1));

    const int f4 = lc.other_face(lc.vertex(f0, f0v0), lc.vertex(f0, f0v1), f0);
    if (f4 < 0 || lc.face_size(f4) != 4)
        return false;
    const int f4v1 = lc.index_in_face(lc.vertex(f0, f0v1), f4);
    if (f4v1 < 0)
        return false;
    const int f4v4 = LocalCell::next_vert(f4v1, 4, lc.owns(f4));
    const int f4v3 = LocalCell::next_vert(f4v4, 4, lc.owns(f4));
    vert[4] = lc.mesh_point(lc.vertex(f4, f4v4));
    vert[3] = lc.mesh_point(lc.vertex(f4, f4v3));

    const int f1 = lc.other_face(lc.vertex(f4, f4v3), lc.vertex(f4, f4v4), f4);
    if (f1 < 0 || lc.face_size(f1) != 3)
        return false;
    if (check_only)
        return true;

    const int f0v2 = LocalCell::next_vert(f0v1, 3, r0);
    vert[2] = lc.mesh_point(lc.vertex(f0, f0v2));
    const int f3 = lc.other_face(lc.vertex(f0, f0v1), lc.vertex(f0, f0v2), f0);
    if (f3 < 0)
        return false;
    const int f3v2 = lc.index_in_face(lc.vertex(f0, f0v2), f3);
    if (f3v2 < 0)
        return false;
    const int f3v5 = LocalCell::next_vert(f3v2, lc.face_size(f3), lc.owns(f3));
    vert[5] = lc.mesh_point(lc.vertex(f3, f3v5));
    return true;
}

// wedgeMatcher::matchShape(checkOnly = true): for some rotation of the first triangle, the
// face across the edge from vertex 0 to vertex 1 is a quad.
bool is_wedge(LocalCell& lc, int n_faces)
{
    if (!lc.prepare(7))
        return false;
    int f0 = -1;
    for (int lf = 0; lf < n_faces && f0 < 0; ++lf)
        if (lc.face_size(lf) == 3)
            f0 = lf;
    const bool r0 = !lc.owns(f0);
    for (int f0v0 = 0; f0v0 < 3; ++f0v0)
    {
        const int f0v1 = LocalCell::next_vert(f0v0, 3, r0);
        const int f4 = lc.other_face(lc.vertex(f0, f0v0), lc.vertex(f0, f0v1), f0);
        if (f4 == -2)
            return false;
        if (f4 >= 0 && lc.face_size(f4) == 4)
            return true;
    }
    return false;
}

CellShape classify_one(const PolyMesh& mesh, std::span<const Index> faces, Index cell)
{
    const SizeCount c = count_face_sizes(mesh, faces);
    if (sizes_are(c, faces.size(), 0, 6))
        return CellShape::hex;
    if (sizes_are(c, faces.size(), 4, 0))
        return CellShape::tet;
    if (sizes_are(c, faces.size(), 4, 1))
        return CellShape::pyramid;
    const int n_faces = static_cast<int>(faces.size());
    if (sizes_are(c, faces.size(), 2, 3))
    {
        LocalCell lc(mesh, faces, cell);
        VertLabels unused;
        if (match_prism(lc, unused, n_faces, true))
            return CellShape::prism;
    }
    if (sizes_are(c, faces.size(), 2, 4))
    {
        LocalCell lc(mesh, faces, cell);
        if (is_wedge(lc, n_faces))
            return CellShape::wedge;
    }
    if (sizes_are(c, faces.size(), 2, 2))
        return CellShape::tet_wedge;
    return CellShape::polyhedron;
}

// OpenFOAM's cell models (etc/cellModels): faces in model vertex numbering, outward by the
// right-hand rule.
struct Model
{
    int n_vert;
    std::vector<std::vector<int>> faces;
};

const Model hex_model{
    8, {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}}};
const Model prism_model{6, {{0, 2, 1}, {3, 4, 5}, {0, 3, 5, 2}, {1, 2, 5, 4}, {0, 1, 4, 3}}};
const Model pyramid_model{5, {{0, 3, 2, 1}, {0, 4, 3}, {3, 4, 2}, {1, 2, 4}, {0, 1, 4}}};
const Model tet_model{4, {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

// Whether a and b are the same cycle up to rotation.
bool same_cycle(std::span<const Index> a, std::span<const Index> b)
{
    if (a.size() != b.size() || a.empty())
        return false;
    const std::size_t n = a.size();
    for (std::size_t s = 0; s < n; ++s)
    {
        bool equal = true;
        for (std::size_t i = 0; i < n && equal; ++i)
            equal = a[i] == b[(i + s) % n];
        if (equal)
            return true;
    }
    return false;
}

// Vertex i of the cell's face f, oriented out of the cell: a neighbour's face is reversed
// keeping vertex 0 (OpenFOAM's face::reverseFace).
Index outward_vertex(std::span<const Index> face, bool owned, std::size_t i)
{
    return owned || i == 0 ? face[i] : face[face.size() - i];
}

// Every outward cell face equals exactly one model face (as an oriented cycle) and vice versa.
// Guards the native VTK cell against walks that succeed on a malformed cell.
bool faces_match_model(const PolyMesh& mesh, std::span<const Index> faces, Index cell,
                       const VertLabels& vert, const Model& model)
{
    if (faces.size() != model.faces.size())
        return false;
    for (int i = 0; i < model.n_vert; ++i)
        for (int j = i + 1; j < model.n_vert; ++j)
            if (vert[i] == vert[j])
                return false;
    std::array<char, max_face> used{};
    std::array<Index, max_face_size> out{};
    std::array<Index, max_face_size> model_face{};
    for (Index f : faces)
    {
        const std::span<const Index> face = mesh.faces[f];
        if (face.size() > static_cast<std::size_t>(max_face_size))
            return false;
        const bool owned = mesh.owner[f] == cell;
        for (std::size_t i = 0; i < face.size(); ++i)
            out[i] = outward_vertex(face, owned, i);
        const std::span<const Index> out_span(out.data(), face.size());
        bool found = false;
        for (std::size_t m = 0; m < model.faces.size() && !found; ++m)
        {
            if (used[m] || model.faces[m].size() != face.size())
                continue;
            for (std::size_t i = 0; i < face.size(); ++i)
                model_face[i] = vert[model.faces[m][i]];
            if (same_cycle(out_span, std::span<const Index>(model_face.data(), face.size())))
            {
                used[m] = 1;
                found = true;
            }
        }
        if (!found)
            return false;
    }
    return true;
}

// VTK_POLYHEDRON: distinct points (first appearance) and the outward face stream.
void polyhedron_cell(const PolyMesh& mesh, std::span<const Index> faces, Index cell,
                     std::vector<Index>& points, std::vector<Index>& stream)
{
    stream.push_back(static_cast<Index>(faces.size()));
    for (Index f : faces)
    {
        const std::span<const Index> face = mesh.faces[f];
        const bool owned = mesh.owner[f] == cell;
        stream.push_back(static_cast<Index>(face.size()));
        for (std::size_t i = 0; i < face.size(); ++i)
        {
            const Index p = outward_vertex(face, owned, i);
            stream.push_back(p);
            if (std::find(points.begin(), points.end(), p) == points.end())
                points.push_back(p);
        }
    }
}

} // namespace

std::string_view checkmesh_name(CellShape shape)
{
    switch (shape)
    {
    case CellShape::hex:
        return "hexahedra";
    case CellShape::prism:
        return "prisms";
    case CellShape::wedge:
        return "wedges";
    case CellShape::pyramid:
        return "pyramids";
    case CellShape::tet_wedge:
        return "tet wedges";
    case CellShape::tet:
        return "tetrahedra";
    case CellShape::polyhedron:
        return "polyhedra";
    }
    return "polyhedra";
}

std::vector<CellShape> classify_cells(const PolyMesh& mesh, const CompactList& cell_faces)
{
    const Index n_cells = cell_faces.size();
    std::vector<CellShape> shapes(static_cast<std::size_t>(n_cells));
    // Threads only pay off on large meshes (a parallel region costs ~10-100 us, more when
    // the machine is oversubscribed).
#pragma omp parallel for schedule(static) if (n_cells > 20000)
    for (Index c = 0; c < n_cells; ++c)
        shapes[c] = classify_one(mesh, cell_faces[c], c);
    return shapes;
}

Index CellShapeCounts::count(CellShape shape) const
{
    switch (shape)
    {
    case CellShape::hex:
        return hex;
    case CellShape::prism:
        return prism;
    case CellShape::wedge:
        return wedge;
    case CellShape::pyramid:
        return pyramid;
    case CellShape::tet_wedge:
        return tet_wedge;
    case CellShape::tet:
        return tet;
    case CellShape::polyhedron:
        return polyhedron;
    }
    return 0;
}

CellShapeCounts count_cell_shapes(const std::vector<CellShape>& shapes,
                                  const CompactList& cell_faces)
{
    if (static_cast<Index>(shapes.size()) != cell_faces.size())
        throw InvalidInput("count_cell_shapes: " + std::to_string(shapes.size()) + " shapes for " +
                           std::to_string(cell_faces.size()) + " cells");
    CellShapeCounts counts;
    for (std::size_t c = 0; c < shapes.size(); ++c)
    {
        switch (shapes[c])
        {
        case CellShape::hex:
            ++counts.hex;
            break;
        case CellShape::prism:
            ++counts.prism;
            break;
        case CellShape::wedge:
            ++counts.wedge;
            break;
        case CellShape::pyramid:
            ++counts.pyramid;
            break;
        case CellShape::tet_wedge:
            ++counts.tet_wedge;
            break;
        case CellShape::tet:
            ++counts.tet;
            break;
        case CellShape::polyhedron:
            ++counts.polyhedron;
            ++counts.polyhedra_by_faces[cell_faces.item_size(static_cast<Index>(c))];
            break;
        }
    }
    return counts;
}

VtkCellType vtk_cell(const PolyMesh& mesh, const CompactList& cell_faces, Index cell,
                     CellShape shape, std::vector<Index>& points, std::vector<Index>& face_stream)
{
    if (cell < 0 || cell >= cell_faces.size())
        throw InvalidInput("vtk_cell: cell " + std::to_string(cell) + " out of range [0, " +
                           std::to_string(cell_faces.size()) + ")");
    points.clear();
    face_stream.clear();
    const std::span<const Index> faces = cell_faces[cell];
    const int n_faces = static_cast<int>(faces.size());
    VertLabels vert{};
    LocalCell lc(mesh, faces, cell);
    switch (shape)
    {
    case CellShape::hex:
        if (match_hex(lc, vert) && faces_match_model(mesh, faces, cell, vert, hex_model))
        {
            points.assign(vert.begin(), vert.begin() + 8);
            return VtkCellType::hexahedron;
        }
        break;
    case CellShape::tet:
        if (match_tet(lc, vert) && faces_match_model(mesh, faces, cell, vert, tet_model))
        {
            points.assign(vert.begin(), vert.begin() + 4);
            return VtkCellType::tetra;
        }
        break;
    case CellShape::pyramid:
        if (match_pyramid(lc, vert, n_faces) &&
            faces_match_model(mesh, faces, cell, vert, pyramid_model))
        {
            points.assign(vert.begin(), vert.begin() + 5);
            return VtkCellType::pyramid;
        }
        break;
    case CellShape::prism:
        if (match_prism(lc, vert, n_faces, false) &&
            faces_match_model(mesh, faces, cell, vert, prism_model))
        {
            // VTK's wedge has its first triangle wound towards the second (foamToVTK's order).
            points.assign({vert[0], vert[2], vert[1], vert[3], vert[5], vert[4]});
            return VtkCellType::wedge;
        }
        break;
    default:
        break;
    }
    polyhedron_cell(mesh, faces, cell, points, face_stream);
    return VtkCellType::polyhedron;
}

VtkCell vtk_cell(const PolyMesh& mesh, const CompactList& cell_faces, Index cell, CellShape shape)
{
    VtkCell result;
    result.type = vtk_cell(mesh, cell_faces, cell, shape, result.points, result.face_stream);
    return result;
}

VtkCells vtk_cells(const PolyMesh& mesh, const CompactList& cell_faces,
                   const std::vector<CellShape>& shapes)
{
    if (static_cast<Index>(shapes.size()) != cell_faces.size())
        throw InvalidInput("vtk_cells: " + std::to_string(shapes.size()) + " shapes for " +
                           std::to_string(cell_faces.size()) + " cells");
    VtkCells result;
    const Index n_cells = cell_faces.size();
    result.types.reserve(static_cast<std::size_t>(n_cells));
    result.points.values.reserve(static_cast<std::size_t>(n_cells) * 8);
    result.points.offsets.reserve(static_cast<std::size_t>(n_cells) + 1);
    result.face_streams.offsets.reserve(static_cast<std::size_t>(n_cells) + 1);
    std::vector<Index> points;
    std::vector<Index> stream;
    for (Index c = 0; c < n_cells; ++c)
    {
        result.types.push_back(vtk_cell(mesh, cell_faces, c, shapes[c], points, stream));
        result.points.push_back(std::span<const Index>(points));
        result.face_streams.push_back(std::span<const Index>(stream));
    }
    return result;
}

} // namespace meshmorph
