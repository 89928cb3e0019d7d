// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Small meshes of every cell shape (tet, pyramid, prism, wedge, tet-wedge, polyhedra)
//! built from per-cell face loops, plus an ASCII polyMesh writer for checkMesh comparisons.
#pragma once

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph::test
{

//! One cell as a list of vertex loops (any orientation; made outward by mesh_from_cells).
using CellLoops = std::vector<std::vector<Index>>;

//! Signed volume of a closed cell by the divergence theorem (fan around the vertex average
//! of each face), positive when the loops are oriented outwards.
inline double loops_volume(const Points& points, const CellLoops& cell)
{
    double v = 0.0;
    for (const auto& loop : cell)
    {
        Vector3 c = Vector3::Zero();
        for (Index p : loop)
            c += points.row(p).transpose();
        c /= static_cast<double>(loop.size());
        for (std::size_t i = 0; i < loop.size(); ++i)
        {
            const Vector3 a = points.row(loop[i]).transpose();
            const Vector3 b = points.row(loop[(i + 1) % loop.size()]).transpose();
            v += c.dot(a.cross(b)) / 6.0;
        }
    }
    return v;
}

//! Orients the loops of a closed cell consistently (each edge traversed once each way),
//! then outwards (positive loops_volume).
inline void orient_cell(const Points& points, CellLoops& cell)
{
    const auto reverse = [](std::vector<Index>& loop)
    { std::reverse(loop.begin() + 1, loop.end()); };
    const auto has_directed_edge = [](const std::vector<Index>& loop, Index a, Index b)
    {
        for (std::size_t i = 0; i < loop.size(); ++i)
            if (loop[i] == a && loop[(i + 1) % loop.size()] == b)
                return true;
        return false;
    };
    std::vector<char> done(cell.size(), 0);
    std::vector<std::size_t> queue{0};
    done[0] = 1;
    while (!queue.empty())
    {
        const std::size_t f = queue.back();
        queue.pop_back();
        const std::vector<Index>& loop = cell[f];
        for (std::size_t i = 0; i < loop.size(); ++i)
        {
            const Index a = loop[i];
            const Index b = loop[(i + 1) % loop.size()];
            for (std::size_t g = 0; g < cell.size(); ++g)
            {
                if (done[g])
                    continue;
                if (has_directed_edge(cell[g], a, b))
                    reverse(cell[g]);
                if (has_directed_edge(cell[g], b, a))
                {
                    done[g] = 1;
                    queue.push_back(g);
                }
            }
        }
    }
    if (loops_volume(points, cell) < 0)
        for (auto& loop : cell)
            reverse(loop);
}

//! A PolyMesh from cells given as face loops. Faces shared by two cells (same vertex set)
//! become internal faces, owner = lower cell, in upper-triangular order; the others go to one
//! patch "walls" in cell order. Every cell is first oriented by orient_cell, so faces point
//! out of the owner as OpenFOAM requires.
inline PolyMesh mesh_from_cells(const Points& points, std::vector<CellLoops> cells)
{
    for (auto& cell : cells)
        orient_cell(points, cell);

    struct Use
    {
        Index cell;
        std::size_t loop;
    };
    std::map<std::vector<Index>, std::vector<Use>> uses;
    for (std::size_t c = 0; c < cells.size(); ++c)
        for (std::size_t l = 0; l < cells[c].size(); ++l)
        {
            std::vector<Index> key = cells[c][l];
            std::sort(key.begin(), key.end());
            uses[key].push_back({static_cast<Index>(c), l});
        }

    struct Internal
    {
        Index own, nei;
        std::vector<Index> loop;
    };
    std::vector<Internal> internal;
    std::vector<std::pair<Index, std::vector<Index>>> boundary;
    for (std::size_t c = 0; c < cells.size(); ++c)
        for (std::size_t l = 0; l < cells[c].size(); ++l)
        {
            std::vector<Index> key = cells[c][l];
            std::sort(key.begin(), key.end());
            const std::vector<Use>& u = uses[key];
            if (u.size() == 1)
                boundary.push_back({static_cast<Index>(c), cells[c][l]});
            else if (u[0].cell == static_cast<Index>(c) && u[0].loop == l)
                internal.push_back({u[0].cell, u[1].cell, cells[c][l]});
        }
    std::stable_sort(internal.begin(), internal.end(),
                     [](const Internal& a, const Internal& b)
                     { return a.own != b.own ? a.own < b.own : a.nei < b.nei; });

    PolyMesh mesh;
    mesh.points = points;
    for (const Internal& f : internal)
    {
        mesh.faces.push_back(std::span<const Index>(f.loop));
        mesh.owner.push_back(f.own);
        mesh.neighbour.push_back(f.nei);
    }
    Patch walls;
    walls.name = "walls";
    walls.type = "wall";
    walls.start_face = mesh.n_faces();
    for (const auto& [own, loop] : boundary)
    {
        mesh.faces.push_back(std::span<const Index>(loop));
        mesh.owner.push_back(own);
    }
    walls.n_faces = mesh.n_faces() - walls.start_face;
    mesh.patches.push_back(walls);
    mesh.finalize();
    return mesh;
}

//! Unit cube corners in OpenFOAM's hex order (0..3 bottom counter-clockwise from +z, 4..7 top).
inline Points cube_points()
{
    Points p(8, 3);
    p << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
    return p;
}

//! Faces of OpenFOAM's hex model over vertex labels v (etc/cellModels).
inline CellLoops hex_loops(const std::array<Index, 8>& v)
{
    return {{v[0], v[4], v[7], v[3]}, {v[1], v[2], v[6], v[5]}, {v[0], v[1], v[5], v[4]},
            {v[3], v[7], v[6], v[2]}, {v[0], v[3], v[2], v[1]}, {v[4], v[5], v[6], v[7]}};
}
inline CellLoops prism_loops(const std::array<Index, 6>& v)
{
    return {{v[0], v[2], v[1]},
            {v[3], v[4], v[5]},
            {v[0], v[3], v[5], v[2]},
            {v[1], v[2], v[5], v[4]},
            {v[0], v[1], v[4], v[3]}};
}
inline CellLoops pyramid_loops(const std::array<Index, 5>& v)
{
    return {{v[0], v[3], v[2], v[1]},
            {v[0], v[4], v[3]},
            {v[3], v[4], v[2]},
            {v[1], v[2], v[4]},
            {v[0], v[1], v[4]}};
}
inline CellLoops tet_loops(const std::array<Index, 4>& v)
{
    return {{v[1], v[2], v[3]}, {v[0], v[3], v[2]}, {v[0], v[1], v[3]}, {v[0], v[2], v[1]}};
}

//! The unit cube cut into 6 tetrahedra around the diagonal 0-6 (Kuhn subdivision).
inline PolyMesh make_tet_cube()
{
    std::vector<CellLoops> cells;
    for (const auto& t : std::vector<std::array<Index, 4>>{
             {0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}})
        cells.push_back(tet_loops(t));
    return mesh_from_cells(cube_points(), cells);
}

//! The unit cube cut into 6 pyramids, one per face, with the apex at the centre (point 8).
inline PolyMesh make_pyramid_cube()
{
    Points p(9, 3);
    p.topRows(8) = cube_points();
    p.row(8) << 0.5, 0.5, 0.5;
    std::vector<CellLoops> cells;
    for (const auto& f : hex_loops({0, 1, 2, 3, 4, 5, 6, 7}))
        cells.push_back(pyramid_loops({f[0], f[1], f[2], f[3], 8}));
    return mesh_from_cells(p, cells);
}

//! The unit cube cut into 2 prisms by the diagonal plane through 0, 2, 6, 4.
inline PolyMesh make_prism_cube()
{
    return mesh_from_cells(cube_points(),
                           {prism_loops({0, 1, 2, 4, 5, 6}), prism_loops({0, 2, 3, 4, 6, 7})});
}

//! A hex (cell 0, z in [-1, 0]) under an OpenFOAM wedge (cell 1): the unit cube with its top
//! back edge 6-7 collapsed to its midpoint, 7 vertices, 2 triangles and 4 quads.
inline PolyMesh make_wedge_on_hex()
{
    Points p(11, 3);
    p << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0.5, 1, 1, // 0..6 (6 = apex)
        0, 0, -1, 1, 0, -1, 1, 1, -1, 0, 1, -1;                           // 7..10 below
    const CellLoops wedge{{0, 4, 6, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                          {3, 6, 2},    {0, 3, 2, 1}, {4, 5, 6}};
    return mesh_from_cells(p, {hex_loops({7, 8, 9, 10, 0, 1, 2, 3}), wedge});
}

//! One OpenFOAM tet-wedge: 5 vertices, 2 triangles and 2 quads, 7 edges. The two quads
//! share three vertices, so no tet-wedge has planar faces (the quad (0 1 2 3) is warped);
//! it is a topology fixture.
inline PolyMesh make_tet_wedge()
{
    Points p(5, 3);
    p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1;
    return mesh_from_cells(p, {{{0, 1, 2, 3}, {1, 0, 4, 2}, {0, 3, 4}, {2, 4, 3}}});
}

//! Unit cube whose top face is split into two triangles: a 7-face polyhedron.
inline PolyMesh make_split_top_cube()
{
    return mesh_from_cells(cube_points(), {{{0, 4, 7, 3},
                                            {1, 2, 6, 5},
                                            {0, 1, 5, 4},
                                            {3, 7, 6, 2},
                                            {0, 3, 2, 1},
                                            {4, 5, 6},
                                            {4, 6, 7}}});
}

//! Two polyhedra. Cell "front" is the unit cube with mid-edge points 8 = (0.5 0 1) and
//! 9 = (0.5 1 1) and its top split into two quads: 2 pentagons + 5 quads = 7 faces. Cell
//! "back" (y in [1, 2]) shares the pentagon (3 7 9 6 2) and has the pentagon top (7 9 6 12 13):
//! 2 pentagons + 4 quads = 6 faces, so it is not a hex although it has 6 faces.
inline PolyMesh make_pentagon_cells()
{
    Points p(14, 3);
    p << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1, // 0..7
        0.5, 0, 1, 0.5, 1, 1,                                                    // 8, 9
        1, 2, 0, 0, 2, 0, 1, 2, 1, 0, 2, 1;                                      // 10..13
    const CellLoops front{{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 8, 4}, {3, 7, 9, 6, 2},
                          {0, 3, 2, 1}, {4, 8, 9, 7}, {8, 5, 6, 9}};
    const CellLoops back{{3, 7, 9, 6, 2},   {11, 10, 12, 13}, {3, 2, 10, 11},
                         {7, 9, 6, 12, 13}, {3, 11, 13, 7},   {2, 6, 12, 10}};
    return mesh_from_cells(p, {front, back});
}

//! The unit cube with vertex 7 merged into 6 while every face keeps 4 labels (two faces
//! repeat vertex 6): 6 "quads", 7 distinct vertices. checkMesh counts it as a hexahedron
//! (hexMatcher::isA looks at face sizes only).
inline PolyMesh make_collapsed_hex()
{
    PolyMesh mesh;
    mesh.points = cube_points();
    for (const auto& f : std::vector<std::vector<Index>>{
             {0, 4, 6, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 6, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 6}})
    {
        mesh.faces.push_back(std::span<const Index>(f));
        mesh.owner.push_back(0);
    }
    Patch walls;
    walls.name = "walls";
    walls.type = "wall";
    walls.start_face = 0;
    walls.n_faces = 6;
    mesh.patches.push_back(walls);
    mesh.finalize();
    return mesh;
}

//! Writes mesh as an ASCII OpenFOAM case (constant/polyMesh and a minimal system/controlDict)
//! so that checkMesh can read it.
inline void write_foam_case(const PolyMesh& mesh, const std::filesystem::path& case_dir)
{
    const std::filesystem::path dir = case_dir / "constant" / "polyMesh";
    std::filesystem::create_directories(dir);
    std::filesystem::create_directories(case_dir / "system");
    const auto header = [](std::ofstream& os, const std::string& cls, const std::string& obj)
    {
        os << "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class " << cls
           << ";\n    location \"constant/polyMesh\";\n    object " << obj << ";\n}\n\n";
    };
    {
        std::ofstream os(case_dir / "system" / "controlDict");
        os << "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
              "    object controlDict;\n}\napplication none;\nstartFrom startTime;\n"
              "startTime 0;\nstopAt endTime;\nendTime 1;\ndeltaT 1;\nwriteControl timeStep;\n"
              "writeInterval 1;\nwriteFormat ascii;\nwritePrecision 6;\n";
    }
    {
        std::ofstream os(case_dir / "system" / "fvSchemes");
        os << "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
              "    object fvSchemes;\n}\nddtSchemes { default steadyState; }\n"
              "gradSchemes { default Gauss linear; }\ndivSchemes { default none; }\n"
              "laplacianSchemes { default Gauss linear corrected; }\n"
              "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n";
    }
    {
        std::ofstream os(case_dir / "system" / "fvSolution");
        os << "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
              "    object fvSolution;\n}\n";
    }
    {
        std::ofstream os(dir / "points");
        os.precision(17);
        header(os, "vectorField", "points");
        os << mesh.n_points() << "\n(\n";
        for (Index i = 0; i < mesh.n_points(); ++i)
            os << "(" << mesh.points(i, 0) << " " << mesh.points(i, 1) << " " << mesh.points(i, 2)
               << ")\n";
        os << ")\n";
    }
    {
        std::ofstream os(dir / "faces");
        header(os, "faceList", "faces");
        os << mesh.n_faces() << "\n(\n";
        for (Index f = 0; f < mesh.n_faces(); ++f)
        {
            os << mesh.faces.item_size(f) << "(";
            const auto face = mesh.faces[f];
            for (std::size_t i = 0; i < face.size(); ++i)
                os << (i ? " " : "") << face[i];
            os << ")\n";
        }
        os << ")\n";
    }
    const auto write_labels = [&](const std::string& name, const std::vector<Index>& labels)
    {
        std::ofstream os(dir / name);
        header(os, "labelList", name);
        os << labels.size() << "\n(\n";
        for (Index l : labels)
            os << l << "\n";
        os << ")\n";
    };
    write_labels("owner", mesh.owner);
    write_labels("neighbour", mesh.neighbour);
    {
        std::ofstream os(dir / "boundary");
        header(os, "polyBoundaryMesh", "boundary");
        os << mesh.patches.size() << "\n(\n";
        for (const Patch& patch : mesh.patches)
            os << patch.name << "\n{\n    type " << patch.type << ";\n    nFaces " << patch.n_faces
               << ";\n    startFace " << patch.start_face << ";\n}\n";
        os << ")\n";
    }
}

} // namespace meshmorph::test
