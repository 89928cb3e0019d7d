// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of io/surface_io.h: STL (ascii, binary) and OBJ, plain and gzip, error messages, and
// OpenFOAM's surfaceCheck on tutorial surfaces.
#include "meshmorph/io/surface_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

#include <zlib.h>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"

using namespace meshmorph;
using namespace meshmorph::io;

namespace
{

// Unit cube as 12 outward triangles (corner p = (i, j, k) bits).
std::vector<std::array<Vector3, 3>> cube_triangles()
{
    const auto c = [](int i) { return Vector3(i & 1, (i >> 1) & 1, (i >> 2) & 1); };
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::vector<std::array<Vector3, 3>> tris;
    for (const auto& q : quads)
    {
        tris.push_back({c(q[0]), c(q[1]), c(q[2])});
        tris.push_back({c(q[0]), c(q[2]), c(q[3])});
    }
    return tris;
}

std::string ascii_stl(const std::vector<std::array<Vector3, 3>>& tris)
{
    std::ostringstream os;
    os.precision(17);
    os << "solid cube made by a test\n";
    for (const auto& t : tris)
    {
        os << "  facet normal 0 0 0\n    outer loop\n";
        for (const Vector3& p : t)
            os << "      vertex " << p.x() << " " << p.y() << " " << p.z() << "\n";
        os << "    endloop\n  endfacet\n";
    }
    os << "endsolid cube\n";
    return os.str();
}

std::string binary_stl(const std::vector<std::array<Vector3, 3>>& tris, const std::string& header)
{
    std::string data(80, ' ');
    std::memcpy(data.data(), header.data(), std::min<std::size_t>(80, header.size()));
    const auto n = static_cast<std::uint32_t>(tris.size());
    data.append(reinterpret_cast<const char*>(&n), 4);
    for (const auto& t : tris)
    {
        float f[12] = {0, 0, 0};
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k)
                f[3 + 3 * v + k] = static_cast<float>(t[v][k]);
        data.append(reinterpret_cast<const char*>(f), sizeof(f));
        data.append(2, '\0');
    }
    return data;
}

void write_text(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

void write_gz(const std::filesystem::path& path, const std::string& text)
{
    gzFile f = gzopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    gzwrite(f, text.data(), static_cast<unsigned>(text.size()));
    gzclose(f);
}

double enclosed_volume(const TriangleSurface& s)
{
    double v = 0;
    for (Index t = 0; t < s.n_triangles(); ++t)
        v += s.vertices.row(s.triangles(t, 0))
                 .dot(s.vertices.row(s.triangles(t, 1)).cross(s.vertices.row(s.triangles(t, 2)))) /
             6.0;
    return v;
}

template <class F> std::string error_of(F&& f)
{
    try
    {
        f();
    }
    catch (const Error& e)
    {
        return e.what();
    }
    return "(no error)";
}

} // namespace

TEST(SurfaceIo, ascii_binary_and_gzip_stl_read_the_same_indexed_cube)
{
    const std::filesystem::path dir = test::scratch_dir("triangle_surface_stl");
    const auto tris = cube_triangles();
    write_text(dir / "a.stl", ascii_stl(tris));
    // A binary header starting with "solid" (as some exporters write) is still binary.
    write_text(dir / "b.stl", binary_stl(tris, "solid but binary"));
    write_gz(dir / "c.stl.gz", ascii_stl(tris));
    for (const char* name : {"a.stl", "b.stl", "c.stl.gz"})
    {
        SCOPED_TRACE(name);
        const TriangleSurface s = read_surface(dir / name);
        EXPECT_EQ(s.n_vertices(), 8); // corners merged
        EXPECT_EQ(s.n_triangles(), 12);
        EXPECT_NEAR(enclosed_volume(s), 1.0, 1e-15); // closed and outward
        for (Index t = 0; t < 12; ++t)
            for (int v = 0; v < 3; ++v)
                EXPECT_EQ(Vector3(s.vertices.row(s.triangles(t, v))), tris[t][v]);
    }
}

TEST(SurfaceIo, stl_errors_name_file_and_line_or_byte)
{
    const std::filesystem::path dir = test::scratch_dir("triangle_surface_stl_errors");
    std::string text = ascii_stl(cube_triangles());
    const std::size_t at = text.find("vertex", text.find("vertex", text.find("facet", 100)) + 1);
    text.replace(at, 6, "vertx"); // line of that token
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
    write_text(dir / "bad.stl", text);
    const std::string m1 = error_of([&] { read_stl(dir / "bad.stl"); });
    EXPECT_NE(m1.find((dir / "bad.stl").string() + ":" + std::to_string(line) + ":"),
              std::string::npos)
        << m1;
    EXPECT_NE(m1.find("'vertx'"), std::string::npos) << m1;

    std::string number = ascii_stl(cube_triangles());
    number.replace(number.find("vertex 0 0 0") + 9, 1, "nan");
    write_text(dir / "nan.stl", number);
    EXPECT_NE(error_of([&] { read_stl(dir / "nan.stl"); }).find("finite number"),
              std::string::npos);

    std::string binary = binary_stl(cube_triangles(), "binary");
    binary.resize(binary.size() - 7);
    write_text(dir / "short.stl", binary);
    const std::string m2 = error_of([&] { read_stl(dir / "short.stl"); });
    EXPECT_NE(m2.find((dir / "short.stl").string() + ": byte 80"), std::string::npos) << m2;
    EXPECT_NE(m2.find("12 triangles"), std::string::npos) << m2;

    write_text(dir / "empty.stl", "solid x\nendsolid x\n");
    EXPECT_NE(error_of([&] { read_stl(dir / "empty.stl"); }).find("no triangles"),
              std::string::npos);
    EXPECT_THROW(read_stl(dir / "missing.stl"), IoError);
    EXPECT_THROW(read_surface(dir / "x.ply"), InvalidInput);
}

TEST(SurfaceIo, obj_polygons_index_forms_and_errors)
{
    const std::filesystem::path dir = test::scratch_dir("triangle_surface_obj");
    const std::string obj = "# cube\nmtllib x.mtl\no cube\n"
                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                            "v 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\nvn 0 0 1\nvt 0 0\n"
                            "f 1 3 4 2\nf 5/1 6/1 8/1 7/1\nf 1//1 2//1 6//1 5//1\n"
                            "f 3/1/1 7/1/1 8/1/1 4/1/1\ns off\nf -8 -4 -2 -6\nf 2 4 8 6 # x+\n";
    write_text(dir / "cube.obj", obj);
    write_gz(dir / "cube.obj.gz", obj);
    for (const char* name : {"cube.obj", "cube.obj.gz"})
    {
        const TriangleSurface s = read_surface(dir / name);
        EXPECT_EQ(s.n_vertices(), 8);
        EXPECT_EQ(s.n_triangles(), 12);
        EXPECT_NEAR(enclosed_volume(s), 1.0, 1e-15);
    }
    write_text(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n");
    const std::string m = error_of([&] { read_obj(dir / "range.obj"); });
    EXPECT_NE(m.find((dir / "range.obj").string() + ":5:"), std::string::npos) << m;
    write_text(dir / "num.obj", "v 0 0 0\nv 1 zero 0\n");
    EXPECT_NE(error_of([&] { read_obj(dir / "num.obj"); }).find(":2:"), std::string::npos);
    write_text(dir / "two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    EXPECT_NE(error_of([&] { read_obj(dir / "two.obj"); }).find(":3: face with 2"),
              std::string::npos);
}

// OpenFOAM's surfaceCheck on tutorial surfaces (STL, gzipped STL, gzipped OBJ): same
// triangle and point counts, same bounding box (printed to 6 digits).
TEST(SurfaceIo, tutorial_surfaces_match_openfoam_surface_check)
{
    const std::filesystem::path root =
        "/usr/share/doc/openfoam-examples/examples/incompressible/pimpleFoam/RAS";
    const std::vector<std::filesystem::path> files{
        root / "rotatingFanInRoom/constant/triSurface/door.stl",
        root / "rotatingFanInRoom/constant/triSurface/fan.stl.gz",
        root / "wingMotion/wingMotion_snappyHexMesh/constant/triSurface/wing_5degrees.obj.gz",
        root / "propeller/constant/triSurface/propellerStem1.obj.gz"};
    if (!std::filesystem::exists(files[0]))
        GTEST_SKIP() << "openfoam-examples not installed: " << files[0];
    if (!test::openfoam_available())
        GTEST_SKIP() << "OpenFOAM not installed: surfaceCheck comparison skipped";
    const std::filesystem::path dir = test::scratch_dir("triangle_surface_check");
    for (const std::filesystem::path& file : files)
    {
        SCOPED_TRACE(file.filename().string());
        const TriangleSurface s = read_surface(file);
        const std::string log = (dir / (file.filename().string() + ".log")).string();
        const std::string cmd = "cd '" + dir.string() + "' && surfaceCheck '" + file.string() +
                                "' > '" + log + "' 2>&1";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << "see " << log;
        std::ifstream in(log);
        std::stringstream text;
        text << in.rdbuf();
        const std::string out = text.str();
        std::smatch m;
        ASSERT_TRUE(std::regex_search(out, m, std::regex("Triangles +: +([0-9]+)"))) << log;
        EXPECT_EQ(std::stol(m[1]), s.n_triangles());
        ASSERT_TRUE(std::regex_search(out, m, std::regex("Vertices +: +([0-9]+)"))) << log;
        EXPECT_EQ(std::stol(m[1]), s.n_vertices());
        const std::string num = "(-?[0-9.eE+-]+)";
        ASSERT_TRUE(
            std::regex_search(out, m,
                              std::regex("Bounding Box : \\(" + num + " " + num + " " + num +
                                         "\\) \\(" + num + " " + num + " " + num + "\\)")))
            << log;
        const Eigen::RowVector3d lo = s.vertices.colwise().minCoeff();
        const Eigen::RowVector3d hi = s.vertices.colwise().maxCoeff();
        const double size = (hi - lo).norm();
        for (int k = 0; k < 3; ++k)
        {
            // 6 significant digits printed: compare to 1e-5 of the box size.
            EXPECT_NEAR(std::stod(m[1 + k]), lo[k], 1e-5 * size);
            EXPECT_NEAR(std::stod(m[4 + k]), hi[k], 1e-5 * size);
        }
        const SurfaceTree tree(s);
        for (Index v = 0; v < s.n_vertices(); v += 7)
            EXPECT_EQ(tree.closest_point(s.vertices.row(v).transpose()).distance, 0.0);
    }
}

// Surfaces are read like every OpenFOAM file: `X`, or else `X.gz`, gzip recognised by its
// bytes; errors name the file actually read.
TEST(SurfaceIo, reads_the_gz_file_when_the_plain_one_is_missing)
{
    const std::filesystem::path dir = test::scratch_dir("surface_io_gz_fallback");
    const auto tris = cube_triangles();
    write_gz(dir / "only.stl.gz", ascii_stl(tris));
    EXPECT_EQ(read_surface(dir / "only.stl").n_triangles(), 12);
    // A gzip file without the suffix is decompressed too.
    write_gz(dir / "packed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(read_obj(dir / "packed.obj").n_triangles(), 1);

    write_gz(dir / "broken.obj.gz", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    const std::string m = error_of([&] { read_surface(dir / "broken.obj"); });
    EXPECT_NE(m.find((dir / "broken.obj.gz").string() + ":3:"), std::string::npos) << m;

    const std::string missing = error_of([&] { read_surface(dir / "none.stl"); });
    EXPECT_NE(missing.find((dir / "none.stl.gz").string()), std::string::npos) << missing;
}
