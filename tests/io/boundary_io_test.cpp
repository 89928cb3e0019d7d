// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of polyMesh boundary and zone file I/O (io/boundary_io.h).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "helpers.h"
#include "meshmorph/io/boundary_io.h"

using namespace meshmorph;
using namespace meshmorph::io;

namespace
{

template <class F> std::string parse_error_of(F f)
{
    try
    {
        f();
    }
    catch (const ParseError& e)
    {
        return e.what();
    }
    ADD_FAILURE() << "expected a ParseError";
    return {};
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

std::string read_file(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// A boundary with every kind of patch meshmorph meets.
std::vector<Patch> sample_patches()
{
    std::vector<Patch> p(6);
    p[0].name = "walls";
    p[0].type = "wall";
    p[0].start_face = 12;
    p[0].n_faces = 16;
    p[0].in_groups = {"wall"};
    p[0].entries = {{"inGroups", "1(wall)"}};
    p[1].name = "inlet";
    p[1].type = "patch";
    p[1].start_face = 28;
    p[1].n_faces = 4;
    p[1].entries = {{"physicalType", "inlet"}};
    p[2].name = "frontAndBack";
    p[2].type = "empty";
    p[2].start_face = 32;
    p[2].n_faces = 0;
    p[2].in_groups = {"empty"};
    p[2].entries = {{"inGroups", "List<word> 1(empty)"}};
    p[3].name = "cyc_half0";
    p[3].type = "cyclic";
    p[3].start_face = 32;
    p[3].n_faces = 2;
    p[3].in_groups = {"cyclic", "myGroup"};
    p[3].entries = {{"inGroups", "2 ( cyclic myGroup )"}, {"matchTolerance", "0.0001"},
                    {"transform", "rotational"},          {"rotationAxis", "(0 0 1)"},
                    {"rotationCentre", "(0 0 0)"},        {"neighbourPatch", "cyc_half1"}};
    p[4].name = "cyc_half1";
    p[4].type = "cyclic";
    p[4].start_face = 34;
    p[4].n_faces = 2;
    p[4].in_groups = {"cyclic"};
    p[4].entries = {{"inGroups", "1(cyclic)"},
                    {"matchTolerance", "0.0001"},
                    {"transform", "noOrdering"},
                    {"neighbourPatch", "cyc_half0"}};
    p[5].name = "procBoundary0to1";
    p[5].type = "processor";
    p[5].start_face = 36;
    p[5].n_faces = 3;
    p[5].in_groups = {"processor"};
    p[5].entries = {{"inGroups", "1(processor)"},
                    {"matchTolerance", "0.0001"},
                    {"transform", "unknown"},
                    {"myProcNo", "0"},
                    {"neighbProcNo", "1"}};
    return p;
}

TEST(BoundaryIo, patch_list_without_its_size_reads_as_in_openfoam)
{
    // driftFluxFoam/RAS/tank3D ships a boundary list with no count before '('.
    const std::string body =
        "// a comment\n(\n    SYMP3 { type patch; startFace 10; nFaces 3; }\n"
        "    walls { type wall; inGroups 1(wall); startFace 13; nFaces 2; }\n)\n";
    const std::vector<Patch> p = parse_boundary(body, "boundary");
    ASSERT_EQ(p.size(), 2u);
    EXPECT_EQ(p[0].name, "SYMP3");
    EXPECT_EQ(p[0].start_face, 10);
    EXPECT_EQ(p[1].type, "wall");
    EXPECT_EQ(p[1].n_faces, 2);
    EXPECT_THROW(parse_boundary("(\n a { type patch; startFace 0; nFaces 1; }\n", "boundary"),
                 ParseError);
}

} // namespace

TEST(BoundaryIo, reads_openfoam_boundary_and_writes_it_back_identically)
{
    const std::string text = read_file(test::data_path("dict/boundary_cavity"));
    const std::vector<Patch> patches = parse_boundary(text, "boundary_cavity");
    ASSERT_EQ(patches.size(), 3u);
    EXPECT_EQ(patches[0].name, "movingWall");
    EXPECT_EQ(patches[0].type, "wall");
    EXPECT_EQ(patches[0].in_groups, (std::vector<std::string>{"wall"}));
    ASSERT_EQ(patches[0].entries.size(), 1u);
    EXPECT_EQ(patches[0].entries[0].first, "inGroups");
    EXPECT_EQ(patches[0].entries[0].second, "1(wall)");
    EXPECT_EQ(patches[2].type, "empty");
    // The blockMesh conventions (§6.1): patches are contiguous and end at nFaces.
    for (std::size_t i = 1; i < patches.size(); ++i)
        EXPECT_EQ(patches[i].start_face, patches[i - 1].start_face + patches[i - 1].n_faces);

    FoamTokenizer tok(text, "boundary_cavity");
    const FoamHeader h = parse_header(tok);
    EXPECT_EQ(format_header(h) + format_boundary(patches) + format_footer(), text);
}

TEST(BoundaryIo, reads_foam_format_convert_spelling)
{
    // foamFormatConvert rewrites the same boundary with `1 ( wall )` and blank lines.
    const std::vector<Patch> a =
        parse_boundary(read_file(test::data_path("dict/boundary_cavity")), "boundary_cavity");
    const std::vector<Patch> b =
        parse_boundary(read_file(test::data_path("dict/boundary_converted")), "boundary_converted");
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        EXPECT_EQ(a[i].name, b[i].name);
        EXPECT_EQ(a[i].type, b[i].type);
        EXPECT_EQ(a[i].n_faces, b[i].n_faces);
        EXPECT_EQ(a[i].start_face, b[i].start_face);
        EXPECT_EQ(a[i].in_groups, b[i].in_groups);
        EXPECT_EQ(b[i].entries.at(0).second, "1 ( " + a[i].in_groups.at(0) + " )");
    }
}

TEST(BoundaryIo, all_patch_types_round_trip)
{
    const std::vector<Patch> patches = sample_patches();
    const std::string body = format_boundary(patches);
    EXPECT_TRUE(contains(body, "    cyc_half0\n    {\n        type            cyclic;\n"
                               "        inGroups        2 ( cyclic myGroup );\n"
                               "        nFaces          2;\n        startFace       32;\n"
                               "        matchTolerance  0.0001;\n"))
        << body;
    EXPECT_TRUE(contains(body, "        physicalType    inlet;\n        nFaces"));
    const std::vector<Patch> back = parse_boundary(body, "boundary");
    EXPECT_EQ(back, patches);
    EXPECT_EQ(format_boundary(back), body);
}

TEST(BoundaryIo, in_groups_in_all_spellings)
{
    for (const char* spelling :
         {"1(wall)", "1 ( wall )", "List<word> 1(wall)", "(wall)", "1\n(\nwall\n)"})
    {
        const std::string body = std::string("1\n(\nw\n{\ntype wall;\ninGroups ") + spelling +
                                 ";\nnFaces 0;\nstartFace 0;\n}\n)";
        const std::vector<Patch> p = parse_boundary(body, "boundary");
        ASSERT_EQ(p.size(), 1u);
        EXPECT_EQ(p[0].in_groups, (std::vector<std::string>{"wall"})) << spelling;
        EXPECT_EQ(p[0].entries.at(0).second, spelling);
    }
}

TEST(BoundaryIo, builds_in_groups_when_no_verbatim_entry)
{
    std::vector<Patch> p(1);
    p[0].name = "top";
    p[0].type = "wall";
    p[0].n_faces = 1;
    p[0].start_face = 5;
    p[0].in_groups = {"wall", "lid"};
    const std::string body = format_boundary(p);
    EXPECT_TRUE(contains(body, "inGroups        2(wall lid);")) << body;
    EXPECT_EQ(parse_boundary(body, "b")[0].in_groups, p[0].in_groups);
}

TEST(BoundaryIo, missing_or_bad_entries_name_patch_and_line)
{
    std::string m = parse_error_of(
        []
        {
            parse_boundary("2\n(\na\n{\ntype patch;\nnFaces 1;\nstartFace 0;\n}\n"
                           "bad\n{\n    type wall;\n    startFace 1;\n}\n)",
                           "constant/polyMesh/boundary");
        });
    EXPECT_TRUE(contains(m, "constant/polyMesh/boundary:10:") && contains(m, "'bad'") &&
                contains(m, "nFaces"))
        << m;
    m = parse_error_of(
        [] { parse_boundary("1\n(\na\n{\ntype patch;\nnFaces -1;\nstartFace 0;\n}\n)", "b"); });
    EXPECT_TRUE(contains(m, "b:6:") && contains(m, "negative")) << m;
    m = parse_error_of(
        [] { parse_boundary("3\n(\na\n{\ntype patch;\nnFaces 1;\nstartFace 0;\n}\n)", "b"); });
    EXPECT_TRUE(contains(m, "b:9:") && contains(m, "3")) << m;
    m = parse_error_of(
        []
        { parse_boundary("1\n(\na\n{\ntype patch;\nnFaces 1;\nstartFace 0;\n}\nb {}\n)", "b"); });
    EXPECT_TRUE(contains(m, "b:9:")) << m;
    m = parse_error_of(
        [] { parse_boundary("1\n(\na\n{\ntype patch;\nnFaces 1;\nstartFace 0;\n", "b"); });
    EXPECT_TRUE(contains(m, "b:4:") && contains(m, "unterminated")) << m;
}

TEST(BoundaryIo, zones_from_openfoam_round_trip_in_ascii_and_binary)
{
    for (const char* name : {"cellZones", "faceZones", "pointZones"})
    {
        const std::string ascii =
            read_file(test::data_path(std::string("dict/zones_ascii/") + name));
        const std::string binary =
            read_file(test::data_path(std::string("dict/zones_binary/") + name));
        const std::vector<Zone> za = parse_zones(ascii, name);
        const std::vector<Zone> zb = parse_zones(binary, name);
        ASSERT_FALSE(za.empty()) << name;
        // OpenFOAM wrote the same zones in both formats.
        EXPECT_EQ(za, zb) << name;

        FoamTokenizer ta(ascii, name);
        const FoamHeader ha = parse_header(ta);
        EXPECT_EQ(format_header(ha) + format_zones(za) + format_footer(), ascii) << name;
        FoamTokenizer tb(binary, name);
        const FoamHeader hb = parse_header(tb);
        ASSERT_TRUE(hb.is_binary());
        EXPECT_EQ(format_header(hb) + format_zones(zb, FoamFormat::binary, hb.label_bytes) +
                      format_footer(),
                  binary)
            << name;
    }
}

TEST(BoundaryIo, zone_contents_match_the_openfoam_text)
{
    const std::vector<Zone> cells =
        parse_zones(read_file(test::data_path("dict/zones_ascii/cellZones")), "cellZones");
    ASSERT_EQ(cells.size(), 3u);
    EXPECT_EQ(cells[0].name, "blockZone");
    EXPECT_EQ(cells[0].type, "cellZone");
    EXPECT_EQ(cells[0].labels, (std::vector<Index>{0, 1, 3, 4}));
    EXPECT_EQ(cells[1].labels.size(), 12u);
    EXPECT_TRUE(cells[2].labels.empty());
    const std::vector<Zone> faces =
        parse_zones(read_file(test::data_path("dict/zones_binary/faceZones")), "faceZones");
    ASSERT_EQ(faces.size(), 2u);
    EXPECT_EQ(faces[0].labels, (std::vector<Index>{17, 18, 19}));
    EXPECT_EQ(faces[0].flip_map, (std::vector<char>{0, 0, 0}));
    EXPECT_TRUE(faces[1].labels.empty());
    EXPECT_TRUE(faces[1].flip_map.empty());
}

TEST(BoundaryIo, zones_round_trip_with_64bit_labels_and_uniform_lists)
{
    std::vector<Zone> z(2);
    z[0].name = "fz";
    z[0].type = "faceZone";
    z[0].labels = {3, 1, 4, 1, 5, 9, 2, 6, 5, 3, 5};
    z[0].flip_map = {1, 0, 1, 1, 0, 0, 0, 1, 0, 1, 1};
    z[1].name = "pz";
    z[1].type = "pointZone";
    z[1].labels = {7, 7, 7};
    for (int label_bytes : {4, 8})
    {
        FoamHeader h;
        h.format = FoamFormat::binary;
        h.class_name = "regIOobject";
        h.object = "zones";
        h.label_bytes = label_bytes;
        const std::string text =
            format_header(h) + format_zones(z, FoamFormat::binary, label_bytes) + format_footer();
        EXPECT_EQ(parse_zones(text, "zones"), z) << label_bytes;
    }
    const std::string ascii = format_zones(z);
    EXPECT_TRUE(contains(ascii, "pointLabels     List<label> 3{7};")) << ascii;
    FoamHeader h;
    h.class_name = "regIOobject";
    h.object = "pointZones";
    EXPECT_EQ(parse_zones(format_header(h) + ascii + format_footer(), "zones"), z);
}

TEST(BoundaryIo, bad_zones_name_file_and_line)
{
    const std::string head = "FoamFile { version 2.0; format ascii; class regIOobject; }\n";
    std::string m = parse_error_of(
        [&]
        {
            parse_zones(head + "1\n(\nz\n{\n    type faceZone;\nfaceLabels List<label> 2(1 2);\n"
                               "flipMap List<bool> 3{0};\n}\n)",
                        "faceZones");
        });
    EXPECT_TRUE(contains(m, "faceZones:8:") && contains(m, "flipMap")) << m;
    m = parse_error_of(
        [&]
        {
            parse_zones(head +
                            "1\n(\nz\n{\n    type cellZone;\ncellLabels List<label> 2(1 -2);\n}\n)",
                        "cellZones");
        });
    EXPECT_TRUE(contains(m, "cellZones:7:") && contains(m, "negative")) << m;
    m = parse_error_of([&]
                       { parse_zones(head + "1\n(\nz\n{\ncellLabels 0();\n}\n)", "cellZones"); });
    EXPECT_TRUE(contains(m, "cellZones:5:") && contains(m, "type")) << m;
    m = parse_error_of([&] { parse_zones("1\n(\n)", "cellZones"); });
    EXPECT_TRUE(contains(m, "cellZones:1:") && contains(m, "FoamFile")) << m;
}

// Every truncation of real OpenFOAM files fails cleanly: a ParseError naming the file, never
// a crash or another exception type. Truncations inside the list must be rejected.
TEST(BoundaryIo, truncated_files_give_parse_errors)
{
    const std::vector<std::string> names = {"boundary_cavity", "zones_ascii/faceZones",
                                            "zones_binary/cellZones", "zones_binary/faceZones"};
    for (const std::string& name : names)
    {
        const std::string text = read_file(test::data_path("dict/" + name));
        const std::size_t last_close = text.rfind(')');
        ASSERT_NE(last_close, std::string::npos);
        const bool is_boundary = name.find("boundary") != std::string::npos;
        for (std::size_t len = 0; len < text.size(); ++len)
        {
            const std::string cut = text.substr(0, len);
            try
            {
                if (is_boundary)
                    parse_boundary(cut, name);
                else
                    parse_zones(cut, name);
                EXPECT_GT(len, last_close) << name << " truncated to " << len << " bytes parsed";
            }
            catch (const ParseError& e)
            {
                EXPECT_EQ(std::string(e.what()).rfind(name + ":", 0), 0u) << e.what();
            }
            catch (const std::exception& e)
            {
                ADD_FAILURE() << name << " truncated to " << len << ": " << e.what();
            }
        }
    }
}
