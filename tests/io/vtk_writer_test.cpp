// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/io/vtk_writer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCellSizeFilter.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "helpers.h"
#include "meshmorph/core/cell_shapes.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "openfoam_cases.h"
#include "shape_meshes.h"

using namespace meshmorph;

namespace
{

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::filesystem::path& path)
{
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    EXPECT_EQ(reader->GetErrorCode(), 0);
    vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
    return grid;
}

vtkSmartPointer<vtkPolyData> read_vtp(const std::filesystem::path& path)
{
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    EXPECT_EQ(reader->GetErrorCode(), 0);
    vtkSmartPointer<vtkPolyData> poly = reader->GetOutput();
    return poly;
}

// VTK's own cell volumes (vtkCellSizeFilter, which integrates each cell type natively).
std::vector<double> vtk_volumes(vtkUnstructuredGrid* grid)
{
    vtkNew<vtkCellSizeFilter> sizes;
    sizes->SetInputData(grid);
    sizes->ComputeVertexCountOff();
    sizes->ComputeLengthOff();
    sizes->ComputeAreaOff();
    sizes->ComputeVolumeOn();
    sizes->ComputeSumOff();
    sizes->Update();
    vtkDataArray* volume =
        vtkDataSet::SafeDownCast(sizes->GetOutput())->GetCellData()->GetArray("Volume");
    std::vector<double> result;
    for (vtkIdType c = 0; c < volume->GetNumberOfTuples(); ++c)
        result.push_back(volume->GetTuple1(c));
    return result;
}

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

std::string file_text(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST(VtkWriter, vtu_round_trip_points_cells_and_arrays)
{
    const PolyMesh mesh =
        test::make_block_mesh(3, 2, 2,
                              [](double u, double v, double w)
                              {
                                  // Affine (sheared, stretched): planar faces, so every volume
                                  // formula agrees exactly.
                                  return Vector3(u + 0.3 * v, v + 0.2 * w, 2 * w + 0.1 * u);
                              });
    Points displacement(mesh.n_points(), 3);
    for (Index p = 0; p < mesh.n_points(); ++p)
        displacement.row(p) << 0.1 * p, -1.0 / (p + 1), std::sqrt(double(p));
    Eigen::VectorXd quality(mesh.n_cells);
    for (Index c = 0; c < mesh.n_cells; ++c)
        quality[c] = 1.0 / 3.0 + c;
    quality[1] = std::numeric_limits<double>::quiet_NaN();

    const std::filesystem::path dir = test::scratch_dir("vtk_writer_vtu");
    const std::filesystem::path path = dir / "mesh.vtu";
    io::write_vtu(path, mesh, {{"displacement", displacement}}, {{"quality", quality}});

    const vtkSmartPointer<vtkUnstructuredGrid> grid = read_vtu(path);
    ASSERT_EQ(grid->GetNumberOfPoints(), mesh.n_points());
    ASSERT_EQ(grid->GetNumberOfCells(), mesh.n_cells);
    for (Index p = 0; p < mesh.n_points(); ++p)
    {
        double x[3];
        grid->GetPoint(p, x);
        for (int j = 0; j < 3; ++j)
            EXPECT_EQ(x[j], mesh.points(p, j)); // binary doubles: bit-exact
    }
    for (Index c = 0; c < mesh.n_cells; ++c)
        EXPECT_EQ(grid->GetCellType(c), VTK_HEXAHEDRON);

    vtkDataArray* d = grid->GetPointData()->GetArray("displacement");
    ASSERT_NE(d, nullptr);
    ASSERT_EQ(d->GetNumberOfComponents(), 3);
    for (Index p = 0; p < mesh.n_points(); ++p)
        for (int j = 0; j < 3; ++j)
            EXPECT_EQ(d->GetComponent(p, j), displacement(p, j));
    vtkDataArray* q = grid->GetCellData()->GetArray("quality");
    vtkDataArray* ids = grid->GetCellData()->GetArray("cellID");
    ASSERT_NE(q, nullptr);
    ASSERT_NE(ids, nullptr);
    for (Index c = 0; c < mesh.n_cells; ++c)
    {
        if (c == 1)
            EXPECT_TRUE(std::isnan(q->GetTuple1(c)));
        else
            EXPECT_EQ(q->GetTuple1(c), quality[c]);
        EXPECT_EQ(ids->GetTuple1(c), c);
    }

    const CompactList cf = cell_faces(mesh);
    const std::vector<double> volumes = vtk_volumes(grid);
    for (Index c = 0; c < mesh.n_cells; ++c)
    {
        const double expected = mesh_cell_volume(mesh, cf, c);
        EXPECT_GT(volumes[c], 0.0);
        EXPECT_NEAR(volumes[c], expected, 1e-12 * expected) << "cell " << c;
    }
}

TEST(VtkWriter, every_shape_gets_its_vtk_type_and_positive_volume)
{
    struct Case
    {
        std::string name;
        PolyMesh mesh;
        std::vector<int> types;
    };
    const std::vector<Case> cases{
        {"tet", test::make_tet_cube(), std::vector<int>(6, VTK_TETRA)},
        {"pyramid", test::make_pyramid_cube(), std::vector<int>(6, VTK_PYRAMID)},
        {"prism", test::make_prism_cube(), {VTK_WEDGE, VTK_WEDGE}},
        {"wedge", test::make_wedge_on_hex(), {VTK_HEXAHEDRON, VTK_POLYHEDRON}},
        {"split", test::make_split_top_cube(), {VTK_POLYHEDRON}},
        {"pentagon", test::make_pentagon_cells(), {VTK_POLYHEDRON, VTK_POLYHEDRON}}};
    const std::filesystem::path dir = test::scratch_dir("vtk_writer_shapes");
    for (const Case& k : cases)
    {
        SCOPED_TRACE(k.name);
        const std::filesystem::path path = dir / (k.name + ".vtu");
        io::write_vtu(path, k.mesh);
        const vtkSmartPointer<vtkUnstructuredGrid> grid = read_vtu(path);
        ASSERT_EQ(grid->GetNumberOfCells(), static_cast<vtkIdType>(k.types.size()));
        const CompactList cf = cell_faces(k.mesh);
        const std::vector<double> volumes = vtk_volumes(grid);
        for (Index c = 0; c < k.mesh.n_cells; ++c)
        {
            EXPECT_EQ(grid->GetCellType(c), k.types[c]) << "cell " << c;
            const double expected = mesh_cell_volume(k.mesh, cf, c);
            EXPECT_GT(volumes[c], 0.0) << "cell " << c;
            if (grid->GetCellType(c) != VTK_POLYHEDRON)
                EXPECT_NEAR(volumes[c], expected, 1e-12) << "planar-faced cell " << c;
            else
            {
                // The polyhedron's face stream read back from the file encloses the cell's
                // volume with outward faces (VTK's own polyhedron volume depends on its
                // triangulation, so compare our integral of VTK's faces).
                vtkNew<vtkIdList> stream;
                grid->GetFaceStream(c, stream);
                test::CellLoops loops;
                vtkIdType i = 1;
                for (vtkIdType f = 0; f < stream->GetId(0); ++f)
                {
                    const vtkIdType n = stream->GetId(i++);
                    std::vector<Index> loop;
                    for (vtkIdType j = 0; j < n; ++j)
                        loop.push_back(static_cast<Index>(stream->GetId(i++)));
                    loops.push_back(loop);
                }
                EXPECT_EQ(i, stream->GetNumberOfIds());
                EXPECT_NEAR(test::loops_volume(k.mesh.points, loops), expected, 1e-12);
            }
        }
    }
}

TEST(VtkWriter, file_is_appended_raw_zlib_xml)
{
    const std::filesystem::path dir = test::scratch_dir("vtk_writer_format");
    io::write_vtu(dir / "m.vtu", test::make_box_mesh(2, 2, 2));
    io::write_vtp_patches(dir / "b.vtp", test::make_box_mesh(2, 2, 2));
    for (const char* name : {"m.vtu", "b.vtp"})
    {
        const std::string text = file_text(dir / name);
        EXPECT_EQ(text.rfind("<VTKFile type=\"", 0), 0u) << name; // VTK writes no <?xml?>
        EXPECT_NE(text.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos) << name;
        EXPECT_NE(text.find("header_type=\"UInt64\""), std::string::npos) << name;
        EXPECT_NE(text.find("<AppendedData encoding=\"raw\">"), std::string::npos) << name;
        EXPECT_NE(text.find("</VTKFile>"), std::string::npos) << name;
    }
    // Only the two outputs: no temporary file left behind.
    int n_files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir))
        ++n_files;
    EXPECT_EQ(n_files, 2);
}

TEST(VtkWriter, vtp_patches_outward_polygons_with_ids_and_names)
{
    const PolyMesh mesh = test::make_box_mesh(3, 2, 4, Vector3(-1, -1, -1), Vector3(1, 1, 1));
    Eigen::VectorXd height = mesh.points.col(2);
    const std::filesystem::path dir = test::scratch_dir("vtk_writer_vtp");
    io::write_vtp_patches(dir / "all.vtp", mesh, {}, {{"height", height}});
    const vtkSmartPointer<vtkPolyData> poly = read_vtp(dir / "all.vtp");
    const Index n_boundary = mesh.n_faces() - mesh.n_internal_faces();
    ASSERT_EQ(poly->GetNumberOfPolys(), n_boundary);

    vtkStringArray* names =
        vtkStringArray::SafeDownCast(poly->GetFieldData()->GetAbstractArray("PatchNames"));
    ASSERT_NE(names, nullptr);
    ASSERT_EQ(names->GetNumberOfValues(), static_cast<vtkIdType>(mesh.patches.size()));
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        EXPECT_EQ(names->GetValue(p), mesh.patches[p].name);

    vtkDataArray* patch_id = poly->GetCellData()->GetArray("patchID");
    vtkDataArray* face_id = poly->GetCellData()->GetArray("faceID");
    vtkDataArray* point_id = poly->GetPointData()->GetArray("pointID");
    vtkDataArray* h = poly->GetPointData()->GetArray("height");
    ASSERT_TRUE(patch_id && face_id && point_id && h);
    for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
    {
        const Index p = static_cast<Index>(point_id->GetTuple1(i));
        double x[3];
        poly->GetPoint(i, x);
        for (int j = 0; j < 3; ++j)
            EXPECT_EQ(x[j], mesh.points(p, j));
        EXPECT_EQ(h->GetTuple1(i), mesh.points(p, 2));
    }
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < poly->GetNumberOfCells(); ++c)
    {
        const Index f = static_cast<Index>(face_id->GetTuple1(c));
        EXPECT_EQ(mesh.which_patch(f), static_cast<Index>(patch_id->GetTuple1(c)));
        poly->GetCellPoints(c, ids);
        ASSERT_EQ(ids->GetNumberOfIds(), mesh.faces.item_size(f));
        // Same loop, same orientation: out of the box.
        Vector3 centre = Vector3::Zero();
        Vector3 normal = Vector3::Zero();
        for (vtkIdType j = 0; j < ids->GetNumberOfIds(); ++j)
        {
            EXPECT_EQ(point_id->GetTuple1(ids->GetId(j)), mesh.faces[f][j]);
            double a[3], b[3];
            poly->GetPoint(ids->GetId(j), a);
            poly->GetPoint(ids->GetId((j + 1) % ids->GetNumberOfIds()), b);
            normal += Vector3(a[0], a[1], a[2]).cross(Vector3(b[0], b[1], b[2]));
            centre += Vector3(a[0], a[1], a[2]);
        }
        EXPECT_GT(normal.dot(centre), 0.0) << "face " << f << " points into the box";
    }

    // A subset, with per-face data in output order.
    const Index zmax = mesh.find_patch("zMax");
    const Index xmin = mesh.find_patch("xMin");
    const Index n_sub = mesh.patches[zmax].n_faces + mesh.patches[xmin].n_faces;
    Eigen::VectorXd order = Eigen::VectorXd::LinSpaced(n_sub, 0, n_sub - 1);
    io::write_vtp_patches(dir / "sub.vtp", mesh, {zmax, xmin}, {}, {{"order", order}});
    const vtkSmartPointer<vtkPolyData> sub = read_vtp(dir / "sub.vtp");
    ASSERT_EQ(sub->GetNumberOfPolys(), n_sub);
    vtkDataArray* sub_patch = sub->GetCellData()->GetArray("patchID");
    vtkDataArray* sub_order = sub->GetCellData()->GetArray("order");
    for (vtkIdType c = 0; c < n_sub; ++c)
    {
        EXPECT_EQ(sub_patch->GetTuple1(c), c < mesh.patches[zmax].n_faces ? zmax : xmin);
        EXPECT_EQ(sub_order->GetTuple1(c), c);
    }
}

TEST(VtkWriter, bad_input_and_unwritable_path_are_reported)
{
    const PolyMesh mesh = test::make_box_mesh(2, 1, 1);
    const std::filesystem::path dir = test::scratch_dir("vtk_writer_errors");
    const Eigen::VectorXd wrong = Eigen::VectorXd::Zero(mesh.n_cells + 1);
    EXPECT_THROW(io::write_vtu(dir / "a.vtu", mesh, {}, {{"q", wrong}}), InvalidInput);
    EXPECT_THROW(io::write_vtu(dir / "a.vtu", mesh, {}, {{"cellID", Eigen::VectorXd::Zero(2)}}),
                 InvalidInput);
    EXPECT_THROW(io::write_vtu(dir / "a.vtu", mesh, {},
                               {{"q", Eigen::VectorXd::Zero(2)}, {"q", Eigen::VectorXd::Zero(2)}}),
                 InvalidInput);
    EXPECT_THROW(io::write_vtp_patches(dir / "b.vtp", mesh, {6}), InvalidInput);
    EXPECT_THROW(io::write_vtp_patches(dir / "b.vtp", mesh, {0}, {}, {{"x", wrong}}), InvalidInput);

    const std::filesystem::path missing = dir / "no_such_dir" / "m.vtu";
    try
    {
        io::write_vtu(missing, mesh);
        FAIL() << "expected IoError";
    }
    catch (const IoError& e)
    {
        EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
    }

    // Overwriting replaces the file as a whole.
    io::write_vtu(dir / "m.vtu", test::make_box_mesh(3, 3, 3));
    io::write_vtu(dir / "m.vtu", mesh);
    EXPECT_EQ(read_vtu(dir / "m.vtu")->GetNumberOfCells(), 2);
}

// Real OpenFOAM meshes (snappyHexMesh flange and motorBike: hexahedra, prisms, pyramids,
// polyhedra; gmsh tetrahedra): the .vtu has checkMesh's number of cells of each type
// (polyhedra include OpenFOAM's wedges and tet-wedges), every cell has a positive VTK volume,
// and polyhedron face streams enclose the mesh cell volume.
TEST(VtkWriter, openfoam_meshes_keep_checkmesh_cell_types_and_positive_volumes)
{
    if (!test::openfoam_available())
        GTEST_SKIP() << "OpenFOAM not installed: real-mesh VTK export test skipped";
    for (const std::string name : {"tet-gmsh", "flange", "motorbike-coarse"})
    {
        SCOPED_TRACE(name);
        const std::filesystem::path case_dir = test::openfoam_case(name);
        const PolyMesh mesh = io::read_poly_mesh(case_dir).mesh;

        // checkMesh's counts, from the log the case script kept.
        const std::string log = file_text(case_dir / "log.checkMesh");
        std::map<std::string, long> expected;
        for (const char* type :
             {"hexahedra", "prisms", "wedges", "pyramids", "tet wedges", "tetrahedra", "polyhedra"})
        {
            std::smatch m;
            ASSERT_TRUE(std::regex_search(
                log, m, std::regex(std::string("\n    ") + type + ": +([0-9]+)\n")))
                << type;
            expected[type] = std::stol(m[1]);
        }
        const CompactList cf = cell_faces(mesh);
        const std::vector<CellShape> shapes = classify_cells(mesh, cf);
        const CellShapeCounts counts = count_cell_shapes(shapes, cf);
        EXPECT_EQ(counts.hex, expected["hexahedra"]);
        EXPECT_EQ(counts.prism, expected["prisms"]);
        EXPECT_EQ(counts.wedge, expected["wedges"]);
        EXPECT_EQ(counts.pyramid, expected["pyramids"]);
        EXPECT_EQ(counts.tet_wedge, expected["tet wedges"]);
        EXPECT_EQ(counts.tet, expected["tetrahedra"]);
        EXPECT_EQ(counts.polyhedron, expected["polyhedra"]);
        std::map<Index, Index> breakdown;
        const std::size_t table = log.find("Breakdown of polyhedra by number of faces:");
        if (table != std::string::npos)
        {
            std::istringstream rows(
                log.substr(log.find('\n', log.find("faces   number", table)) + 1));
            for (std::string row; std::getline(rows, row) && !row.empty();)
            {
                std::istringstream fields(row);
                Index faces = 0, cells = 0;
                if (!(fields >> faces >> cells))
                    break;
                breakdown[faces] = cells;
            }
        }
        EXPECT_EQ(breakdown, counts.polyhedra_by_faces);

        const std::filesystem::path path = test::scratch_dir("vtk_writer_" + name) / "mesh.vtu";
        io::write_vtu(path, mesh);
        const vtkSmartPointer<vtkUnstructuredGrid> grid = read_vtu(path);
        ASSERT_EQ(grid->GetNumberOfCells(), mesh.n_cells);
        std::map<int, long> by_type;
        for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
            ++by_type[grid->GetCellType(c)];
        // Native cells need the full topology walk, so a checkMesh "hexahedron" with a
        // repeated vertex would become a polyhedron; these meshes have none.
        EXPECT_EQ(by_type[VTK_HEXAHEDRON], counts.hex);
        EXPECT_EQ(by_type[VTK_WEDGE], counts.prism);
        EXPECT_EQ(by_type[VTK_PYRAMID], counts.pyramid);
        EXPECT_EQ(by_type[VTK_TETRA], counts.tet);
        EXPECT_EQ(by_type[VTK_POLYHEDRON], counts.wedge + counts.tet_wedge + counts.polyhedron);

        const std::vector<double> volumes = vtk_volumes(grid);
        long non_positive = 0;
        vtkNew<vtkIdList> stream;
        for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
        {
            non_positive += !(volumes[c] > 0.0);
            if (grid->GetCellType(c) != VTK_POLYHEDRON)
                continue;
            grid->GetFaceStream(c, stream);
            test::CellLoops loops;
            vtkIdType i = 1;
            for (vtkIdType f = 0; f < stream->GetId(0); ++f)
            {
                const vtkIdType n = stream->GetId(i++);
                std::vector<Index> loop;
                for (vtkIdType j = 0; j < n; ++j)
                    loop.push_back(static_cast<Index>(stream->GetId(i++)));
                loops.push_back(loop);
            }
            const double v = mesh_cell_volume(mesh, cf, static_cast<Index>(c));
            EXPECT_NEAR(test::loops_volume(mesh.points, loops), v, 1e-12 * std::abs(v))
                << "cell " << c;
        }
        EXPECT_EQ(non_positive, 0) << "cells with VTK volume <= 0";
    }
}
