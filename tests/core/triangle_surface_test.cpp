// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/core/triangle_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include <zlib.h>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"

using namespace meshmorph;

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

// A bumpy closed sphere: UV grid with radial noise.
TriangleSurface bumpy_sphere(int nu, int nv, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.9, 1.1);
    TriangleSurface s;
    s.vertices.resize(2 + nu * (nv - 1), 3);
    s.vertices.row(0) << 0, 0, 1;
    s.vertices.row(1) << 0, 0, -1;
    for (int j = 1; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
        {
            const double th = M_PI * j / nv, ph = 2 * M_PI * i / nu, r = u(rng);
            s.vertices.row(2 + i + nu * (j - 1)) << r * std::sin(th) * std::cos(ph),
                r * std::sin(th) * std::sin(ph), r * std::cos(th);
        }
    std::vector<std::array<Index, 3>> t;
    const auto id = [&](int i, int j) { return Index(2 + (i % nu) + nu * (j - 1)); };
    for (int i = 0; i < nu; ++i)
    {
        t.push_back({0, id(i, 1), id(i + 1, 1)});
        t.push_back({1, id(i + 1, nv - 1), id(i, nv - 1)});
        for (int j = 1; j + 1 < nv; ++j)
        {
            t.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
            t.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
        }
    }
    s.triangles.resize(static_cast<Eigen::Index>(t.size()), 3);
    for (std::size_t k = 0; k < t.size(); ++k)
        s.triangles.row(static_cast<Eigen::Index>(k)) << t[k][0], t[k][1], t[k][2];
    return s;
}

} // namespace

TEST(TriangleSurface, ascii_binary_and_gzip_stl_read_the_same_indexed_cube)
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

TEST(TriangleSurface, stl_errors_name_file_and_line_or_byte)
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

TEST(TriangleSurface, obj_polygons_index_forms_and_errors)
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

TEST(TriangleSurface, closest_point_on_triangle_regions)
{
    const Vector3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
    EXPECT_EQ(closest_point_on_triangle(Vector3(0.5, 0.5, 3), a, b, c), Vector3(0.5, 0.5, 0));
    EXPECT_EQ(closest_point_on_triangle(Vector3(-1, -1, 1), a, b, c), a);
    EXPECT_EQ(closest_point_on_triangle(Vector3(5, -1, 0), a, b, c), b);
    EXPECT_EQ(closest_point_on_triangle(Vector3(1, -3, 1), a, b, c), Vector3(1, 0, 0));
    EXPECT_TRUE(closest_point_on_triangle(Vector3(2, 2, 0), a, b, c).isApprox(Vector3(1, 1, 0)));
    // Degenerate (collinear) triangle: the closest point of its segments, never NaN.
    const Vector3 p = closest_point_on_triangle(Vector3(1, 1, 0), a, b, Vector3(1, 0, 0));
    EXPECT_EQ(p, Vector3(1, 0, 0));
}

TEST(TriangleSurface, tree_matches_brute_force)
{
    const TriangleSurface s = bumpy_sphere(24, 16, 3);
    const SurfaceTree tree(s);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-3, 3);
    Points queries(400, 3);
    for (Index q = 0; q < queries.rows(); ++q)
        queries.row(q) << u(rng), u(rng), u(rng);
    queries.row(0) << 0, 0, 0;
    queries.row(1) << 100, -50, 7;
    const Points batch = tree.closest_points(queries);
    for (Index q = 0; q < queries.rows(); ++q)
    {
        const Vector3 x = queries.row(q).transpose();
        double best = std::numeric_limits<double>::infinity();
        for (Index t = 0; t < s.n_triangles(); ++t)
            best = std::min(
                best, (closest_point_on_triangle(x, s.vertices.row(s.triangles(t, 0)).transpose(),
                                                 s.vertices.row(s.triangles(t, 1)).transpose(),
                                                 s.vertices.row(s.triangles(t, 2)).transpose()) -
                       x)
                          .norm());
        const SurfacePoint sp = tree.closest_point(x);
        EXPECT_EQ(sp.distance, best) << "query " << q; // same arithmetic, exact
        EXPECT_NEAR((sp.point - x).norm(), sp.distance, 1e-15 * (1 + sp.distance));
        EXPECT_TRUE(Vector3(batch.row(q)).isApprox(sp.point, 1e-15) ||
                    (Vector3(batch.row(q)) - sp.point).norm() < 1e-15);
    }
    // Vertices are on the surface.
    for (Index v = 0; v < s.n_vertices(); ++v)
        EXPECT_EQ(tree.closest_point(s.vertices.row(v).transpose()).distance, 0.0);
}

TEST(TriangleSurface, tree_rejects_bad_surfaces)
{
    EXPECT_THROW(SurfaceTree(TriangleSurface{}), InvalidInput);
    TriangleSurface s = bumpy_sphere(6, 4, 1);
    s.triangles(2, 1) = s.n_vertices();
    EXPECT_THROW(SurfaceTree{s}, InvalidInput);
    s = bumpy_sphere(6, 4, 1);
    s.vertices(3, 0) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(SurfaceTree{s}, InvalidInput);
}

// OpenFOAM's surfaceCheck on tutorial surfaces (STL, gzipped STL, gzipped OBJ): same
// triangle and point counts, same bounding box (printed to 6 digits).
TEST(TriangleSurface, tutorial_surfaces_match_openfoam_surface_check)
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
