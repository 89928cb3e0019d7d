// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of io/read_poly_mesh.h and io/write_poly_mesh.h: generated meshes in every format,
// OpenFOAM-written fixtures (tests/data/io/curved_block), bit-identical round trips, and
// malformed input (tests/data/io/malformed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "io_test_util.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_lists.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"

using namespace meshmorph;
using namespace meshmorph::io;
namespace fs = std::filesystem;

namespace
{

const std::vector<std::string> mesh_files{"points", "faces", "owner", "neighbour", "boundary"};

// A curved, wall-bounded block mesh with zones, as make_block_mesh builds it.
PolyMesh sample_mesh()
{
    PolyMesh mesh = test::make_block_mesh(
        4, 3, 2,
        [](double u, double v, double w)
        { return Vector3(u * 2 + 0.1 * std::sin(3 * v), v + 0.05 * u * u, 0.5 * w + 1e-3 / 3); },
        {"patch", "patch", "wall", "wall", "empty", "empty"});
    Zone cells{"left", "cellZone", {0, 4, 8}, {}, {}};
    Zone faces{"mid", "faceZone", {1, 2}, {0, 1}, {}};
    Zone points{"corner", "pointZone", {0}, {}, {}};
    mesh.cell_zones.push_back(cells);
    mesh.face_zones.push_back(faces);
    mesh.point_zones.push_back(points);
    return mesh;
}

void expect_same_mesh(const PolyMesh& a, const PolyMesh& b)
{
    ASSERT_EQ(a.points.rows(), b.points.rows());
    EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), sizeof(double) * a.points.size()), 0)
        << "points differ";
    EXPECT_EQ(a.faces, b.faces);
    EXPECT_EQ(a.owner, b.owner);
    EXPECT_EQ(a.neighbour, b.neighbour);
    EXPECT_EQ(a.n_cells, b.n_cells);
    ASSERT_EQ(a.patches.size(), b.patches.size());
    for (std::size_t p = 0; p < a.patches.size(); ++p)
    {
        EXPECT_EQ(a.patches[p].name, b.patches[p].name);
        EXPECT_EQ(a.patches[p].type, b.patches[p].type);
        EXPECT_EQ(a.patches[p].start_face, b.patches[p].start_face);
        EXPECT_EQ(a.patches[p].n_faces, b.patches[p].n_faces);
        EXPECT_EQ(a.patches[p].in_groups, b.patches[p].in_groups);
    }
    EXPECT_EQ(a.cell_zones, b.cell_zones);
    EXPECT_EQ(a.face_zones, b.face_zones);
    EXPECT_EQ(a.point_zones, b.point_zones);
}

PolyMeshReadOptions read_at(const TimeSelection& time)
{
    PolyMeshReadOptions o;
    o.time = time;
    return o;
}

struct FormatCase
{
    const char* name;
    FoamFormat format;
    bool compress;
};
const FormatCase all_formats[] = {{"ascii", FoamFormat::ascii, false},
                                  {"binary", FoamFormat::binary, false},
                                  {"ascii_gz", FoamFormat::ascii, true},
                                  {"binary_gz", FoamFormat::binary, true}};

// Decompressed contents of every file in a polyMesh directory, by name without .gz.
std::map<std::string, std::string> dir_contents(const fs::path& dir)
{
    std::map<std::string, std::string> out;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
    {
        std::string name = e.path().filename().string();
        if (name.size() > 3 && name.substr(name.size() - 3) == ".gz")
            name.resize(name.size() - 3);
        out[name] = test::file_text(e.path());
    }
    return out;
}

} // namespace

TEST(PolyMeshIo, generated_mesh_round_trips_in_every_format)
{
    const PolyMesh mesh = sample_mesh();
    for (const FormatCase& fc : all_formats)
    {
        SCOPED_TRACE(fc.name);
        const fs::path case_dir = test::scratch_dir(std::string("pm_roundtrip_") + fc.name);
        write_poly_mesh(mesh, default_poly_mesh_files(fc.format, fc.compress), case_dir,
                        "constant");
        for (const std::string& f : mesh_files)
        {
            const fs::path plain = case_dir / "constant/polyMesh" / f;
            const bool gz = fc.compress && f != "boundary";
            EXPECT_EQ(fs::exists(plain), !gz) << f;
            EXPECT_EQ(fs::exists(fs::path(plain.string() + ".gz")), gz) << f;
        }
        const FoamPolyMesh back = read_poly_mesh(case_dir);
        expect_same_mesh(mesh, back.mesh);
        EXPECT_EQ(back.points.header.format, fc.format);
        EXPECT_EQ(back.points.is_compressed, fc.compress);
        EXPECT_EQ(back.faces.header.class_name,
                  fc.format == FoamFormat::binary ? "faceCompactList" : "faceList");
        EXPECT_EQ(back.points.header.location, "constant/polyMesh");
        EXPECT_EQ(back.owner.header.note, "nPoints:60  nCells:24  nFaces:98  nInternalFaces:46");

        // read -> write -> read -> write: both writes are byte-identical.
        const fs::path again = test::scratch_dir(std::string("pm_roundtrip2_") + fc.name);
        write_poly_mesh(back.mesh, back, again, "constant");
        const FoamPolyMesh back2 = read_poly_mesh(again);
        expect_same_mesh(mesh, back2.mesh);
        const fs::path third = test::scratch_dir(std::string("pm_roundtrip3_") + fc.name);
        write_poly_mesh(back2.mesh, back2, third, "constant");
        for (const fs::directory_entry& e : fs::directory_iterator(again / "constant/polyMesh"))
            EXPECT_EQ(test::file_bytes(e.path()),
                      test::file_bytes(third / "constant/polyMesh" / e.path().filename()))
                << e.path();
    }
}

TEST(PolyMeshIo, owner_note_counts_follow_openfoam)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    const fs::path case_dir = test::scratch_dir("pm_note");
    write_poly_mesh(mesh, default_poly_mesh_files(FoamFormat::ascii), case_dir, "constant");
    const FoamPolyMesh back = read_poly_mesh(case_dir);
    // 27 points, 8 cells, 3*2*2*3 = 36 faces of which 3*4 = 12 internal.
    EXPECT_EQ(back.owner.header.note, "nPoints:27  nCells:8  nFaces:36  nInternalFaces:12");
    EXPECT_EQ(back.neighbour.header.note, back.owner.header.note);
}

TEST(PolyMeshIo, reads_openfoam_fixtures_in_all_formats_identically)
{
    // tests/data/io/curved_block: blockMesh (arc + spline edges, 3x2x2 cells), topoSet +
    // setsToZones, then foamFormatConvert to binary and to compressed ASCII (README.md).
    const FoamPolyMesh ascii = read_poly_mesh(test::data_path("io/curved_block/ascii"));
    const PolyMesh& m = ascii.mesh;
    // Counts from the blockMeshDict: a 3 x 2 x 2 hex block.
    EXPECT_EQ(m.n_points(), 4 * 3 * 3);
    EXPECT_EQ(m.n_cells, 3 * 2 * 2);
    EXPECT_EQ(m.n_faces(), 4 * 2 * 2 + 3 * 3 * 2 + 3 * 2 * 3);
    EXPECT_EQ(m.n_internal_faces(), 2 * 2 * 2 + 3 * 1 * 2 + 3 * 2 * 1);
    ASSERT_EQ(m.patches.size(), 4u);
    EXPECT_EQ(m.patches[2].name, "walls");
    EXPECT_EQ(m.patches[2].type, "wall");
    EXPECT_EQ(m.patches[2].in_groups, std::vector<std::string>{"wall"});
    ASSERT_EQ(m.cell_zones.size(), 1u);
    EXPECT_EQ(m.cell_zones[0].labels.size(), 12u);
    ASSERT_EQ(m.face_zones.size(), 1u);
    EXPECT_EQ(m.face_zones[0].flip_map.size(), m.face_zones[0].labels.size());
    ASSERT_EQ(m.point_zones.size(), 1u);
    EXPECT_EQ(ascii.points_instance, "constant");
    EXPECT_EQ(ascii.points.header.format, FoamFormat::ascii);

    // The arc edge 3-2 through (1 1.3 0) * 0.1 bulges the top: y > 0.1 inside the edge.
    EXPECT_GT(m.points.col(1).maxCoeff(), 0.1 + 1e-3);

    for (const char* variant : {"binary", "gz", "binary_gz"})
    {
        SCOPED_TRACE(variant);
        const FoamPolyMesh other =
            read_poly_mesh(test::data_path(std::string("io/curved_block/") + variant));
        // foamFormatConvert wrote the values it read from the ASCII files: all equal exactly.
        expect_same_mesh(m, other.mesh);
    }
    const FoamPolyMesh binary = read_poly_mesh(test::data_path("io/curved_block/binary"));
    EXPECT_EQ(binary.points.header.format, FoamFormat::binary);
    EXPECT_EQ(binary.points.header.label_bytes, 4);
    EXPECT_EQ(binary.faces.header.class_name, "faceCompactList");
    const FoamPolyMesh gz = read_poly_mesh(test::data_path("io/curved_block/gz"));
    EXPECT_TRUE(gz.points.is_compressed);
    EXPECT_TRUE(gz.faces.is_compressed);
}

TEST(PolyMeshIo, writes_openfoam_files_byte_for_byte)
{
    // Files meshmorph writes from an unchanged mesh equal OpenFOAM's own: all binary mesh
    // files, and the ASCII ones except points (OpenFOAM wrote those at writePrecision 12,
    // meshmorph at 17 digits).
    for (const char* variant : {"binary", "ascii", "gz"})
    {
        SCOPED_TRACE(variant);
        const fs::path source = test::data_path(std::string("io/curved_block/") + variant);
        const FoamPolyMesh m = read_poly_mesh(source);
        const fs::path out = test::scratch_dir(std::string("pm_bytes_") + variant);
        write_poly_mesh(m.mesh, m, out, "constant");
        const std::map<std::string, std::string> theirs =
            dir_contents(source / "constant/polyMesh");
        const std::map<std::string, std::string> ours = dir_contents(out / "constant/polyMesh");
        for (const std::string f : {"points", "faces", "owner", "neighbour"})
        {
            if (f == "points" && std::string(variant) != "binary")
                continue;
            ASSERT_TRUE(ours.count(f)) << f;
            EXPECT_EQ(ours.at(f), theirs.at(f)) << f;
        }
        // Compression is kept per file.
        EXPECT_EQ(fs::exists(out / "constant/polyMesh/points.gz"), std::string(variant) == "gz");
    }
}

TEST(PolyMeshIo, write_points_keeps_format_and_sets_location)
{
    for (const char* variant : {"ascii", "binary", "gz", "binary_gz"})
    {
        SCOPED_TRACE(variant);
        const fs::path case_dir = test::scratch_dir(std::string("pm_points_") + variant);
        test::copy_tree(test::data_path(std::string("io/curved_block/") + variant), case_dir);
        FoamPolyMesh m = read_poly_mesh(case_dir);
        Points moved = m.mesh.points;
        moved.col(0) *= 1.0 / 3.0; // values that need all 17 digits
        const fs::path written = write_points(moved, m.points, case_dir, "1");
        EXPECT_EQ(written.filename().string(), m.points.is_compressed ? "points.gz" : "points");

        const FoamPolyMesh latest = read_poly_mesh(case_dir, read_at(TimeSelection::latest_time()));
        EXPECT_EQ(latest.points_instance, "1");
        EXPECT_EQ(latest.faces_instance, "constant");
        EXPECT_EQ(latest.points.header.location, "1/polyMesh");
        EXPECT_EQ(latest.points.header.format, m.points.header.format);
        EXPECT_EQ(latest.points.is_compressed, m.points.is_compressed);
        EXPECT_EQ(latest.points.header.class_name, "vectorField");
        ASSERT_EQ(latest.mesh.points.rows(), moved.rows());
        EXPECT_EQ(
            std::memcmp(latest.mesh.points.data(), moved.data(), sizeof(double) * moved.size()), 0);
        if (latest.points.header.is_binary())
        {
            EXPECT_EQ(latest.points.header.arch, "LSB;label=32;scalar=64");
        }

        // The original time still reads the original points.
        const FoamPolyMesh first = read_poly_mesh(case_dir, read_at(TimeSelection::at("constant")));
        EXPECT_EQ(first.mesh.points, m.mesh.points);

        // Overwriting in place with the other compression leaves a single file.
        PolyMeshWriteOptions flip;
        flip.compress = !m.points.is_compressed;
        write_points(moved, m.points, case_dir, "constant", "", flip);
        const fs::path dir = case_dir / "constant/polyMesh";
        EXPECT_NE(fs::exists(dir / "points"), fs::exists(dir / "points.gz"));
    }
}

TEST(PolyMeshIo, writes_to_a_region)
{
    const PolyMesh mesh = test::make_box_mesh(1, 1, 1);
    const fs::path case_dir = test::scratch_dir("pm_region");
    write_poly_mesh(mesh, default_poly_mesh_files(FoamFormat::ascii), case_dir, "constant",
                    "solid");
    EXPECT_TRUE(fs::exists(case_dir / "constant/solid/polyMesh/points"));
    PolyMeshReadOptions options;
    options.region = "solid";
    const FoamPolyMesh back = read_poly_mesh(case_dir, options);
    EXPECT_EQ(back.points.header.location, "constant/solid/polyMesh");
    expect_same_mesh(mesh, back.mesh);
    EXPECT_THROW(read_poly_mesh(case_dir), IoError); // no default region
}

TEST(PolyMeshIo, reads_legacy_neighbour_padded_with_minus_one)
{
    const PolyMesh mesh = test::make_box_mesh(2, 1, 1);
    const fs::path case_dir = test::scratch_dir("pm_legacy_neighbour");
    write_poly_mesh(mesh, default_poly_mesh_files(FoamFormat::ascii), case_dir, "constant");
    std::vector<Index> padded = mesh.neighbour;
    padded.resize(static_cast<std::size_t>(mesh.n_faces()), -1);
    PolyMesh legacy = mesh;
    legacy.neighbour = padded;
    // Write the padded list by hand through the writer's label layout.
    std::string body;
    append_label_list(body, padded, FoamFormat::ascii);
    FoamHeader h;
    h.class_name = "labelList";
    h.object = "neighbour";
    test::write_bytes(case_dir / "constant/polyMesh/neighbour",
                      format_header(h) + body + format_footer());
    const FoamPolyMesh back = read_poly_mesh(case_dir);
    EXPECT_EQ(back.mesh.neighbour, mesh.neighbour);
    EXPECT_EQ(back.mesh.n_internal_faces(), mesh.n_internal_faces());
}

TEST(PolyMeshIo, reads_64_bit_labels_and_32_bit_scalars)
{
    const PolyMesh mesh = test::make_box_mesh(2, 2, 1, Vector3(0, 0, 0), Vector3(1, 0.5, 0.25));
    const fs::path case_dir = test::scratch_dir("pm_label64");
    PolyMeshWriteOptions o;
    o.label_bytes = 8;
    write_poly_mesh(mesh, default_poly_mesh_files(FoamFormat::binary), case_dir, "constant", "", o);
    const FoamPolyMesh back = read_poly_mesh(case_dir);
    EXPECT_EQ(back.owner.header.label_bytes, 8);
    EXPECT_EQ(back.owner.header.arch, "LSB;label=64;scalar=64");
    expect_same_mesh(mesh, back.mesh);

    // Single precision points (scalar=32): values representable as float read exactly.
    std::string body = "\n" + std::to_string(mesh.n_points()) + "\n(";
    for (Eigen::Index i = 0; i < mesh.points.size(); ++i)
    {
        const float f = static_cast<float>(mesh.points.data()[i]);
        body.append(reinterpret_cast<const char*>(&f), sizeof f);
    }
    body += ")";
    FoamHeader h;
    h.format = FoamFormat::binary;
    h.class_name = "vectorField";
    h.object = "points";
    h.scalar_bytes = 4;
    h.arch = "LSB;label=32;scalar=32";
    test::write_bytes(case_dir / "constant/polyMesh/points",
                      format_header(h) + body + format_footer());
    const FoamPolyMesh single = read_poly_mesh(case_dir);
    EXPECT_EQ(single.points.header.scalar_bytes, 4);
    EXPECT_EQ(single.mesh.points, mesh.points);
}

// ----------------------------------------------------------------------------------------
// Malformed input: each fixture replaces one file of the ASCII (or binary) curved block.

struct MalformedCase
{
    const char* name;  // directory under tests/data/io/malformed
    const char* file;  // the broken file in it
    const char* base;  // curved_block variant it replaces a file of
    const char* where; // expected "file:line" (or file name) in the message
    const char* what;  // expected words of the message
};

class PolyMeshMalformed : public testing::TestWithParam<MalformedCase>
{
};

TEST_P(PolyMeshMalformed, error_names_file_and_location)
{
    const MalformedCase& c = GetParam();
    const fs::path case_dir = test::scratch_dir(std::string("pm_malformed_") + c.name);
    test::copy_tree(test::data_path(std::string("io/curved_block/") + c.base), case_dir);
    const fs::path dir = case_dir / "constant/polyMesh";
    fs::copy_file(test::data_path(std::string("io/malformed/") + c.name + "/" + c.file),
                  dir / c.file, fs::copy_options::overwrite_existing);
    try
    {
        read_poly_mesh(case_dir);
        ADD_FAILURE() << "no error for " << c.name;
    }
    catch (const ParseError& e)
    {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(std::string("polyMesh/") + c.where), std::string::npos) << msg;
        EXPECT_NE(msg.find(c.what), std::string::npos) << msg;
    }
}

// Line numbers are those of the defects in the fixture files (see malformed/README.md).
INSTANTIATE_TEST_SUITE_P(
    Fixtures, PolyMeshMalformed,
    testing::Values(
        MalformedCase{"truncated_faces", "faces", "ascii", "faces:19:", "declares 52"},
        MalformedCase{"owner_count_mismatch", "owner", "ascii", "owner:73:", "ends after 51"},
        MalformedCase{"face_label_out_of_range", "faces", "ascii",
                      "faces:30:", "vertex label 36 outside [0, 36)"},
        MalformedCase{"face_too_few_vertices", "faces", "ascii", "faces:25:", "at least 3"},
        MalformedCase{"points_wrong_class", "points", "ascii", "points:8:", "wrong class"},
        MalformedCase{"faces_missing_header", "faces", "ascii", "faces:", "FoamFile"},
        MalformedCase{"points_ascii_under_binary", "points", "ascii", "points:", "byte offset"},
        MalformedCase{"points_truncated_binary", "points", "binary", "points:", "remain"},
        MalformedCase{"owner_huge_count", "owner", "ascii", "owner:20:", "1000000000000"},
        MalformedCase{"owner_huge_count_binary", "owner", "binary", "owner:", "1000000000000"},
        MalformedCase{"faces_garbage", "faces", "ascii", "faces:", "faces"},
        MalformedCase{"neighbour_not_upper", "neighbour", "ascii",
                      "neighbour:22:", "owner must be the lower cell"},
        MalformedCase{"owner_negative", "owner", "ascii", "owner:25:", "negative"},
        MalformedCase{"boundary_gap", "boundary", "ascii", "boundary:26:", "outlet"},
        MalformedCase{"faces_binary_label_out_of_range", "faces", "binary",
                      "faces:", "byte offset"},
        MalformedCase{"neighbour_too_long", "neighbour", "ascii",
                      "neighbour:", "more than the 52"}),
    [](const testing::TestParamInfo<MalformedCase>& param_info)
    { return std::string(param_info.param.name); });

TEST(PolyMeshIo, missing_file_is_an_io_error_naming_it)
{
    const fs::path case_dir = test::scratch_dir("pm_missing_owner");
    test::copy_tree(test::data_path("io/curved_block/ascii"), case_dir);
    fs::remove(case_dir / "constant/polyMesh/owner");
    const std::string msg = test::error_of([&] { read_poly_mesh(case_dir); });
    EXPECT_NE(msg.find("constant/polyMesh/owner"), std::string::npos) << msg;
    EXPECT_THROW(read_poly_mesh(test::scratch_dir("pm_empty_case")), IoError);
}

TEST(PolyMeshIo, read_poly_mesh_dir_reads_one_directory)
{
    const FoamPolyMesh a =
        read_poly_mesh_dir(test::data_path("io/curved_block/gz/constant/polyMesh"));
    const FoamPolyMesh b = read_poly_mesh(test::data_path("io/curved_block/ascii"));
    expect_same_mesh(a.mesh, b.mesh);
    EXPECT_TRUE(a.case_dir.empty());
    EXPECT_GT(a.total_bytes(), 0u);
}

TEST(PolyMeshIo, random_corruptions_give_errors_not_crashes)
{
    // Byte flips, truncations and insertions in every mesh file of the ASCII and binary
    // fixtures: each read either succeeds (the damage was harmless, e.g. in a comment) or
    // throws a meshmorph::Error naming the damaged file. Run under ASan in the asan preset.
    std::mt19937 rng(20261121);
    const fs::path case_dir = test::scratch_dir("pm_fuzz");
    log::CaptureScope quiet; // damaged headers give warnings
    int n_errors = 0;
    for (const char* variant : {"ascii", "binary"})
    {
        const fs::path source = test::data_path(std::string("io/curved_block/") + variant);
        test::copy_tree(source, case_dir);
        for (const std::string& f : mesh_files)
        {
            const std::string original = test::file_bytes(source / "constant/polyMesh" / f);
            for (int trial = 0; trial < 25; ++trial)
            {
                std::string damaged = original;
                std::uniform_int_distribution<std::size_t> pos(0, damaged.size() - 1);
                switch (trial % 3)
                {
                case 0:
                    for (int k = 0; k < 4; ++k)
                        damaged[pos(rng)] = static_cast<char>(rng() & 0xff);
                    break;
                case 1:
                    damaged.resize(pos(rng));
                    break;
                default:
                    damaged.insert(pos(rng), std::to_string(rng() % 100000000));
                    break;
                }
                test::write_bytes(case_dir / "constant/polyMesh" / f, damaged);
                try
                {
                    read_poly_mesh(case_dir);
                }
                catch (const Error& e)
                {
                    ++n_errors;
                    EXPECT_NE(std::string(e.what()).find("polyMesh/"), std::string::npos)
                        << e.what();
                }
            }
            test::write_bytes(case_dir / "constant/polyMesh" / f, original);
        }
    }
    EXPECT_GT(n_errors, 100); // most damage must be detected
}

TEST(PolyMeshIo, format_conversion_matches_foam_format_convert)
{
    // The binary and gz fixtures are foamFormatConvert's conversions of the ASCII one;
    // meshmorph converting the same mesh must produce the same files.
    const FoamPolyMesh ascii = read_poly_mesh(test::data_path("io/curved_block/ascii"));
    const struct
    {
        const char* variant;
        FoamFormat format;
        bool compress;
    } targets[] = {{"binary", FoamFormat::binary, false}, {"gz", FoamFormat::ascii, true}};
    for (const auto& t : targets)
    {
        SCOPED_TRACE(t.variant);
        PolyMeshWriteOptions o;
        o.format = t.format;
        o.compress = t.compress;
        const fs::path out = test::scratch_dir(std::string("pm_convert_") + t.variant);
        write_poly_mesh(ascii.mesh, ascii, out, "constant", "", o);
        const std::map<std::string, std::string> theirs = dir_contents(
            test::data_path(std::string("io/curved_block/") + t.variant) / "constant/polyMesh");
        const std::map<std::string, std::string> ours = dir_contents(out / "constant/polyMesh");
        for (const std::string f : {"points", "faces", "owner", "neighbour"})
        {
            if (f == "points" && t.format == FoamFormat::ascii)
                continue; // OpenFOAM printed 12 digits, meshmorph 17
            EXPECT_EQ(ours.at(f), theirs.at(f)) << f;
        }
        const FoamPolyMesh back = read_poly_mesh(out);
        expect_same_mesh(ascii.mesh, back.mesh);
        EXPECT_EQ(back.faces.header.class_name,
                  t.format == FoamFormat::binary ? "faceCompactList" : "faceList");
    }
}

TEST(PolyMeshIo, write_points_warns_about_stale_tet_base_points)
{
    const fs::path case_dir = test::scratch_dir("pm_tetbase");
    test::copy_tree(test::data_path("io/curved_block/ascii"), case_dir);
    test::write_bytes(case_dir / "constant/polyMesh/tetBasePtIs", "x");
    const FoamPolyMesh m = read_poly_mesh(case_dir);
    EXPECT_TRUE(m.has_tet_base_pt_is);
    log::CaptureScope capture;
    write_points(m.mesh.points, m.points, case_dir, "constant");
    EXPECT_NE(capture.text().find("tetBasePtIs"), std::string::npos) << capture.text();
}

TEST(PolyMeshIo, binary_face_list_and_ascii_face_compact_list_round_trip)
{
    // The two rarer combinations of docs/polymesh-format.md §5.2, kept when rewriting.
    const PolyMesh mesh = sample_mesh();
    for (const FoamFormat format : {FoamFormat::binary, FoamFormat::ascii})
    {
        FoamPolyMesh like = default_poly_mesh_files(format);
        like.faces.header.class_name =
            format == FoamFormat::binary ? "faceList" : "faceCompactList";
        const fs::path case_dir = test::scratch_dir(
            std::string("pm_face_classes_") + (format == FoamFormat::binary ? "bin" : "ascii"));
        write_poly_mesh(mesh, like, case_dir, "constant");
        const FoamPolyMesh back = read_poly_mesh(case_dir);
        EXPECT_EQ(back.faces.header.class_name, like.faces.header.class_name);
        EXPECT_EQ(back.faces.header.format, format);
        expect_same_mesh(mesh, back.mesh);
    }
}
