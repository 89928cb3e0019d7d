// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/core/cell_shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "shape_meshes.h"

using namespace meshmorph;

namespace
{

CellShapeCounts counts_of(const PolyMesh& mesh)
{
    const CompactList cf = cell_faces(mesh);
    return count_cell_shapes(classify_cells(mesh, cf), cf);
}

// VTK's own face lists (vtkTetra/vtkPyramid/vtkWedge/vtkHexahedron::GetFaceArray), used to
// check that a native cell's vertices really span the mesh cell's faces.
std::vector<std::vector<int>> vtk_faces(VtkCellType type)
{
    switch (type)
    {
    case VtkCellType::tetra:
        return {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 1}};
    case VtkCellType::pyramid:
        return {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    case VtkCellType::wedge:
        return {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}};
    case VtkCellType::hexahedron:
        return {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
    default:
        return {};
    }
}

// Volume of a native VTK cell from its VTK faces (outward in VTK's convention), so a positive
// value means the vertex order has VTK's orientation.
double vtk_native_volume(const PolyMesh& mesh, const VtkCell& cell)
{
    test::CellLoops loops;
    for (const auto& f : vtk_faces(cell.type))
    {
        std::vector<Index> loop;
        for (int v : f)
            loop.push_back(cell.points[v]);
        loops.push_back(loop);
    }
    return test::loops_volume(mesh.points, loops);
}

// Volume of a polyhedron from its face stream.
double face_stream_volume(const PolyMesh& mesh, const VtkCell& cell)
{
    test::CellLoops loops;
    std::size_t i = 1;
    for (Index f = 0; f < cell.face_stream[0]; ++f)
    {
        const Index n = cell.face_stream[i++];
        loops.emplace_back(cell.face_stream.begin() + i, cell.face_stream.begin() + i + n);
        i += n;
    }
    EXPECT_EQ(i, cell.face_stream.size());
    return test::loops_volume(mesh.points, loops);
}

// Mesh cell volume from the mesh's own faces (neighbour faces reversed).
double mesh_cell_volume(const PolyMesh& mesh, const CompactList& cf, Index c)
{
    test::CellLoops loops;
    for (Index f : cf[c])
    {
        std::vector<Index> loop(mesh.faces[f].begin(), mesh.faces[f].end());
        if (mesh.owner[f] != c)
            std::reverse(loop.begin(), loop.end());
        loops.push_back(loop);
    }
    return test::loops_volume(mesh.points, loops);
}

// Every native VTK cell: right vertex count, VTK faces = the mesh cell's faces as vertex sets,
// volume equal to the mesh cell's; polyhedra: face stream encloses the cell's volume.
void expect_vtk_cells_consistent(const PolyMesh& mesh)
{
    const CompactList cf = cell_faces(mesh);
    const std::vector<CellShape> shapes = classify_cells(mesh, cf);
    for (Index c = 0; c < mesh.n_cells; ++c)
    {
        const VtkCell cell = vtk_cell(mesh, cf, c, shapes[c]);
        const double volume = mesh_cell_volume(mesh, cf, c);
        ASSERT_GT(volume, 0.0) << "fixture cell " << c;
        if (cell.type == VtkCellType::polyhedron)
        {
            EXPECT_NEAR(face_stream_volume(mesh, cell), volume, 1e-12 * volume) << "cell " << c;
            continue;
        }
        EXPECT_TRUE(cell.face_stream.empty());
        std::set<std::vector<Index>> mesh_faces, vtk_face_sets;
        for (Index f : cf[c])
        {
            std::vector<Index> s(mesh.faces[f].begin(), mesh.faces[f].end());
            std::sort(s.begin(), s.end());
            mesh_faces.insert(s);
        }
        for (const auto& f : vtk_faces(cell.type))
        {
            std::vector<Index> s;
            for (int v : f)
                s.push_back(cell.points[v]);
            std::sort(s.begin(), s.end());
            vtk_face_sets.insert(s);
        }
        EXPECT_EQ(mesh_faces, vtk_face_sets) << "cell " << c;
        // Same volume from VTK's faces: exact up to rounding (both are sums of the same
        // triangle fans up to face rotation).
        EXPECT_NEAR(vtk_native_volume(mesh, cell), volume, 1e-12 * volume) << "cell " << c;
    }
}

} // namespace

TEST(CellShapes, box_mesh_is_all_hexahedra)
{
    const PolyMesh mesh = test::make_box_mesh(3, 2, 2);
    const CellShapeCounts counts = counts_of(mesh);
    EXPECT_EQ(counts.hex, 12);
    EXPECT_EQ(counts.polyhedron, 0);
    EXPECT_TRUE(counts.polyhedra_by_faces.empty());
    const CompactList cf = cell_faces(mesh);
    const std::vector<CellShape> shapes = classify_cells(mesh, cf);
    for (Index c = 0; c < mesh.n_cells; ++c)
        EXPECT_EQ(vtk_cell(mesh, cf, c, shapes[c]).type, VtkCellType::hexahedron);
    expect_vtk_cells_consistent(mesh);
}

TEST(CellShapes, distorted_block_hexes_keep_vtk_orientation)
{
    const PolyMesh mesh = test::make_block_mesh(
        3, 3, 2,
        [](double u, double v, double w)
        { return Vector3(u + 0.2 * v * v, v + 0.1 * std::sin(3 * u), w * (1 + 0.3 * u)); });
    EXPECT_EQ(counts_of(mesh).hex, 18);
    expect_vtk_cells_consistent(mesh);
}

TEST(CellShapes, tetrahedra)
{
    const PolyMesh mesh = test::make_tet_cube();
    const CellShapeCounts counts = counts_of(mesh);
    EXPECT_EQ(counts.tet, 6);
    EXPECT_EQ(counts.tet, mesh.n_cells);
    expect_vtk_cells_consistent(mesh);
}

TEST(CellShapes, pyramids)
{
    const PolyMesh mesh = test::make_pyramid_cube();
    const CellShapeCounts counts = counts_of(mesh);
    EXPECT_EQ(counts.pyramid, 6);
    const CompactList cf = cell_faces(mesh);
    const std::vector<CellShape> shapes = classify_cells(mesh, cf);
    for (Index c = 0; c < mesh.n_cells; ++c)
    {
        const VtkCell cell = vtk_cell(mesh, cf, c, shapes[c]);
        ASSERT_EQ(cell.type, VtkCellType::pyramid);
        EXPECT_EQ(cell.points[4], 8) << "apex is VTK vertex 4";
    }
    expect_vtk_cells_consistent(mesh);
}

TEST(CellShapes, prisms_owner_and_neighbour)
{
    const PolyMesh mesh = test::make_prism_cube();
    ASSERT_EQ(mesh.n_internal_faces(), 1);
    const CellShapeCounts counts = counts_of(mesh);
    EXPECT_EQ(counts.prism, 2);
    const CompactList cf = cell_faces(mesh);
    const std::vector<CellShape> shapes = classify_cells(mesh, cf);
    for (Index c = 0; c < mesh.n_cells; ++c)
        EXPECT_EQ(vtk_cell(mesh, cf, c, shapes[c]).type, VtkCellType::wedge);
    expect_vtk_cells_consistent(mesh);
}

TEST(CellShapes, openfoam_wedge_is_degenerate_hex)
{
    const PolyMesh mesh = test::make_wedge_on_hex();
    const CompactList cf = cell_faces(mesh);
    const std::vector<CellShape> shapes = classify_cells(mesh, cf);
    ASSERT_EQ(shapes.size(), 2u);
    EXPECT_EQ(shapes[0], CellShape::hex);
    EXPECT_EQ(shapes[1], CellShape::wedge);
    EXPECT_EQ(vtk_cell(mesh, cf, 1, shapes[1]).type, VtkCellType::polyhedron);
    expect_vtk_cells_consistent(mesh);
}

TEST(CellShapes, tet_wedge)
{
    const PolyMesh mesh = test::make_tet_wedge();
    const CellShapeCounts counts = counts_of(mesh);
    EXPECT_EQ(counts.tet_wedge, 1);
    const CompactList cf = cell_faces(mesh);
    EXPECT_EQ(vtk_cell(mesh, cf, 0, CellShape::tet_wedge).type, VtkCellType::polyhedron);
}

TEST(CellShapes, polyhedra_breakdown_by_face_count)
{
    const PolyMesh split = test::make_split_top_cube();
    const CellShapeCounts a = counts_of(split);
    EXPECT_EQ(a.polyhedron, 1);
    EXPECT_EQ(a.polyhedra_by_faces, (std::map<Index, Index>{{7, 1}}));

    const PolyMesh pent = test::make_pentagon_cells();
    const CellShapeCounts b = counts_of(pent);
    EXPECT_EQ(b.hex, 0) << "6 faces with pentagons are not a hex";
    EXPECT_EQ(b.polyhedron, 2);
    EXPECT_EQ(b.polyhedra_by_faces, (std::map<Index, Index>{{6, 1}, {7, 1}}));
    expect_vtk_cells_consistent(split);
    expect_vtk_cells_consistent(pent);
}

TEST(CellShapes, six_quads_with_repeated_vertex_count_as_hex_but_export_as_polyhedron)
{
    // OpenFOAM's hexMatcher::isA tests face sizes only, so checkMesh counts this collapsed
    // cube as a hexahedron (counts_match_openfoam_checkmesh checks that with checkMesh).
    const PolyMesh mesh = test::make_collapsed_hex();
    const CompactList cf = cell_faces(mesh);
    const std::vector<CellShape> shapes = classify_cells(mesh, cf);
    EXPECT_EQ(shapes[0], CellShape::hex);
    const VtkCell cell = vtk_cell(mesh, cf, 0, shapes[0]);
    EXPECT_EQ(cell.type, VtkCellType::polyhedron);
    EXPECT_EQ(cell.points.size(), 7u);
}

TEST(CellShapes, face_rotation_and_cell_face_order_do_not_change_classification)
{
    // Rotating every face's vertex list (same geometry and orientation) changes which vertex
    // the matchers start from, never the class.
    PolyMesh mesh = test::make_prism_cube();
    const CellShapeCounts before = counts_of(mesh);
    CompactList rotated;
    for (Index f = 0; f < mesh.n_faces(); ++f)
    {
        std::vector<Index> loop(mesh.faces[f].begin(), mesh.faces[f].end());
        std::rotate(loop.begin(), loop.begin() + (f % loop.size()), loop.end());
        rotated.push_back(std::span<const Index>(loop));
    }
    mesh.faces = rotated;
    EXPECT_EQ(counts_of(mesh), before);
    expect_vtk_cells_consistent(mesh);
}

TEST(CellShapes, invalid_arguments_throw)
{
    const PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    const CompactList cf = cell_faces(mesh);
    EXPECT_THROW(vtk_cell(mesh, cf, 1, CellShape::hex), InvalidInput);
    EXPECT_THROW(count_cell_shapes({}, cf), InvalidInput);
    EXPECT_THROW(vtk_cells(mesh, cf, {}), InvalidInput);
    // A wrong shape hint never produces a wrong native cell: the walk fails, polyhedron.
    EXPECT_EQ(vtk_cell(mesh, cf, 0, CellShape::tet).type, VtkCellType::polyhedron);
}

TEST(CellShapes, vtk_cells_flattens_per_cell_results)
{
    const PolyMesh mesh = test::make_pentagon_cells();
    const CompactList cf = cell_faces(mesh);
    const std::vector<CellShape> shapes = classify_cells(mesh, cf);
    const VtkCells all = vtk_cells(mesh, cf, shapes);
    ASSERT_EQ(all.types.size(), 2u);
    for (Index c = 0; c < 2; ++c)
    {
        const VtkCell one = vtk_cell(mesh, cf, c, shapes[c]);
        EXPECT_EQ(all.types[c], one.type);
        EXPECT_TRUE(std::ranges::equal(all.points[c], one.points));
        EXPECT_TRUE(std::ranges::equal(all.face_streams[c], one.face_stream));
    }
}

// checkMesh itself on every fixture: the "Overall number of cells of each type" block and the
// polyhedra breakdown must match count_cell_shapes.
TEST(CellShapes, counts_match_openfoam_checkmesh)
{
    if (!test::openfoam_available())
        GTEST_SKIP() << "OpenFOAM not installed: checkMesh cell-type comparison skipped";
    const std::vector<std::pair<std::string, PolyMesh>> cases{
        {"hex", test::make_box_mesh(2, 2, 1)},        {"tet", test::make_tet_cube()},
        {"pyramid", test::make_pyramid_cube()},       {"prism", test::make_prism_cube()},
        {"wedge", test::make_wedge_on_hex()},         {"tetwedge", test::make_tet_wedge()},
        {"split", test::make_split_top_cube()},       {"pentagon", test::make_pentagon_cells()},
        {"collapsed-hex", test::make_collapsed_hex()}};
    const std::filesystem::path root = test::scratch_dir("cell_shapes_checkmesh");
    for (const auto& [name, mesh] : cases)
    {
        SCOPED_TRACE(name);
        const std::filesystem::path dir = root / name;
        test::write_foam_case(mesh, dir);
        const std::string log = (dir / "log.checkMesh").string();
        const std::string cmd = "checkMesh -case '" + dir.string() + "' > '" + log + "' 2>&1";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << "see " << log;
        std::ifstream in(log);
        std::stringstream text;
        text << in.rdbuf();
        const std::string out = text.str();
        const CellShapeCounts counts = counts_of(mesh);
        for (CellShape shape :
             {CellShape::hex, CellShape::prism, CellShape::wedge, CellShape::pyramid,
              CellShape::tet_wedge, CellShape::tet, CellShape::polyhedron})
        {
            const std::regex re("\n    " + std::string(checkmesh_name(shape)) + ": +([0-9]+)\n");
            std::smatch m;
            ASSERT_TRUE(std::regex_search(out, m, re)) << checkmesh_name(shape) << " in " << log;
            EXPECT_EQ(std::stol(m[1]), counts.count(shape)) << checkmesh_name(shape);
        }
        std::map<Index, Index> breakdown;
        const std::regex row("\n {8,}([0-9]+) +([0-9]+)(?=\n)");
        for (auto it = std::sregex_iterator(out.begin(), out.end(), row);
             it != std::sregex_iterator(); ++it)
            breakdown[std::stol((*it)[1])] = std::stol((*it)[2]);
        EXPECT_EQ(breakdown, counts.polyhedra_by_faces);
    }
}
