// SPDX-License-Identifier: GPL-3.0-or-later
// Oracle tests of checkMeshQuality (meshmorph/app/check_mesh_case.h, quality/check_mesh.h):
// OpenFOAM's own checkMesh runs on real meshes generated at test time (blockMesh with curved
// edges, gmsh tetrahedra, snappyHexMesh, deliberately damaged meshes, binary and compressed
// files) and its report is compared, line by line, with ours. Nothing is typed in: the
// expected text is parsed from checkMesh's output at test time.
//
// Comparison rule: the lines from "Mesh stats" to "Mesh OK."/"Failed N mesh checks." must
// have the same words; numbers that are integers must be equal; other numbers must agree to
// 1e-6 relative, plus 1e-12 absolute for rounding-noise values near zero (the openness of a
// closed boundary is a sum of O(1) terms that cancel to 1e-17..1e-15). The cases use
// writePrecision 15, so checkMesh prints 15 digits.
#include <gtest/gtest.h>

#include "check_mesh_run.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "helpers.h"
#include "meshmorph/app/check_mesh_case.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"
#include "openfoam_cases.h"

namespace fs = std::filesystem;
using namespace meshmorph;

namespace
{

std::vector<std::string> split_lines(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    return lines;
}

//! The report block of a checkMesh(-like) output: "Mesh stats" .. the verdict line, without
//! "<<Writing" set lines (checkMesh always writes sets; we do only with -writeSets).
std::vector<std::string> report_block(const std::string& text, bool keep_set_lines = false)
{
    std::vector<std::string> block;
    bool inside = false;
    for (const std::string& line : split_lines(text))
    {
        if (line == "Mesh stats")
            inside = true;
        if (!inside)
            continue;
        if (!keep_set_lines && line.find("  <<Writing") == 0)
            continue;
        block.push_back(line);
        if (line == "Mesh OK." || line.rfind("Failed ", 0) == 0)
            break;
    }
    return block;
}

std::vector<std::string> tokens(const std::string& line)
{
    std::string spaced;
    for (char ch : line)
    {
        if (ch == '(' || ch == ')' || ch == ',')
            spaced += ' ';
        spaced += ch;
        if (ch == '(' || ch == ')' || ch == ',')
            spaced += ' ';
    }
    std::istringstream in(spaced);
    std::vector<std::string> result;
    for (std::string t; in >> t;)
    {
        // "0.225." -> number and the sentence's full stop.
        if (t.size() > 1 && t.back() == '.' &&
            std::isdigit(static_cast<unsigned char>(t[t.size() - 2])))
        {
            result.push_back(t.substr(0, t.size() - 1));
            result.push_back(".");
        }
        else
            result.push_back(t);
    }
    return result;
}

bool parse_number(const std::string& token, double& value, bool& is_integer)
{
    static const std::regex number(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
    if (!std::regex_match(token, number))
        return false;
    value = std::stod(token);
    is_integer = token.find_first_of(".eE") == std::string::npos;
    return true;
}

//! Compare two report blocks; returns "" when they agree, else a description.
std::string compare_reports(const std::vector<std::string>& expected,
                            const std::vector<std::string>& actual)
{
    std::ostringstream diff;
    if (expected.size() != actual.size())
        diff << "line count " << actual.size() << " != checkMesh's " << expected.size() << "\n";
    const std::size_t n = std::min(expected.size(), actual.size());
    for (std::size_t i = 0; i < n; ++i)
    {
        const std::vector<std::string> e = tokens(expected[i]), a = tokens(actual[i]);
        bool same = e.size() == a.size();
        for (std::size_t k = 0; same && k < e.size(); ++k)
        {
            double ve = 0, va = 0;
            bool ie = false, ia = false;
            if (parse_number(e[k], ve, ie) && parse_number(a[k], va, ia))
            {
                if (ie && ia)
                    same = ve == va;
                else
                    same = std::abs(ve - va) <= 1e-6 * std::max(std::abs(ve), std::abs(va)) + 1e-12;
            }
            else
                same = e[k] == a[k];
        }
        if (!same)
            diff << "line " << i << ":\n  checkMesh: " << expected[i]
                 << "\n  ours:      " << actual[i] << "\n";
    }
    return diff.str();
}

std::string read_text(const fs::path& path)
{
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

//! Run OpenFOAM's checkMesh in `case_dir` with `args`; returns its stdout.
std::string run_checkmesh(const fs::path& case_dir, const std::string& args)
{
    const fs::path log = case_dir / "log.checkMesh.oracle";
    const std::string command =
        "cd '" + case_dir.string() + "' && checkMesh " + args + " > '" + log.string() + "' 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return read_text(log);
}

test::AppRun run_ours(const fs::path& case_dir, std::vector<std::string> args)
{
    args.insert(args.begin(), {"-case", case_dir.string()});
    return test::run_check_mesh_quality(args);
}

//! A private copy of a generated case (checkMesh writes sets into the case).
fs::path copy_case(const std::string& name, const std::string& scratch)
{
    const fs::path source = test::openfoam_case(name);
    const fs::path dir = test::scratch_dir(scratch);
    fs::copy(source, dir, fs::copy_options::recursive);
    return dir;
}

//! Without checkMesh's AMI lines (-allGeometry's writeAMIWeightsSums and the AMI
//! construction it triggers), which checkMeshQuality does not print (docs/checkMeshQuality.md).
std::vector<std::string> without_ami_lines(std::vector<std::string> block)
{
    std::erase_if(block, [](const std::string& line)
                  { return line.rfind("AMI: ", 0) == 0 || line.rfind("Calculating AMI", 0) == 0; });
    return block;
}

//! The labels of an OpenFOAM list file (a set or cellToRegion): the integers after the
//! header's divider line, without the leading size, which must match their number.
//! (checkMesh writes a set in its hash table's order: compare sets sorted.)
std::vector<long> list_file_labels(const fs::path& path, bool sorted = false)
{
    const std::string text = read_text(path);
    const std::size_t divider = text.find("// * * *");
    EXPECT_NE(divider, std::string::npos) << path;
    std::string body = text.substr(text.find('\n', divider));
    body = body.substr(0, body.find("// ****"));
    for (char& c : body)
        if (c == '(' || c == ')')
            c = ' ';
    std::istringstream in(body);
    std::vector<long> labels;
    for (long v; in >> v;)
        labels.push_back(v);
    EXPECT_FALSE(labels.empty()) << path;
    if (labels.empty())
        return labels;
    EXPECT_EQ(labels[0], static_cast<long>(labels.size() - 1)) << path;
    labels.erase(labels.begin());
    if (sorted)
        std::sort(labels.begin(), labels.end());
    return labels;
}

//! The part of an OpenFOAM file after its header's divider line.
std::string after_header(const fs::path& path)
{
    const std::string text = read_text(path);
    const std::size_t divider = text.find("// * * *");
    return divider == std::string::npos ? "" : text.substr(text.find('\n', divider));
}

//! Compare checkMesh and checkMeshQuality on `name` with the given options.
void expect_same_report(const std::string& name, const std::vector<std::string>& options)
{
    std::string joined, scratch = "quality_oracle_" + name;
    for (const std::string& o : options)
    {
        joined += " " + o;
        scratch += o;
    }
    const fs::path dir = copy_case(name, scratch);
    const std::string theirs = run_checkmesh(dir, joined);
    const test::AppRun ours = run_ours(dir, options);
    ASSERT_TRUE(ours.status == 0 || ours.status == 1) << ours.err;
    const std::vector<std::string> expected = report_block(theirs);
    ASSERT_GT(expected.size(), 10u) << "no checkMesh report parsed:\n" << theirs;
    EXPECT_EQ(compare_reports(expected, report_block(ours.out)), "")
        << "case " << name << ", options" << joined;
    // Exit status mirrors the verdict.
    EXPECT_EQ(ours.status == 0, expected.back() == "Mesh OK.");
}

#define REQUIRE_OPENFOAM(what)                                                                     \
    if (!test::openfoam_available())                                                               \
    GTEST_SKIP() << "OpenFOAM not installed: " what " not compared with checkMesh"

const std::vector<std::string> all_checks = {"-allGeometry", "-allTopology"};

} // namespace

TEST(CheckMeshOracle, report_comparison_rejects_a_changed_number)
{
    // The comparison itself must notice a 1e-5 relative change and a changed count.
    const std::vector<std::string> a = {"Mesh stats", "    Max skewness = 0.0435500178548794 OK.",
                                        "    cells:            336"};
    std::vector<std::string> b = a;
    b[1] = "    Max skewness = 0.0435504 OK.";
    EXPECT_NE(compare_reports(a, b), "");
    b = a;
    b[2] = "    cells:            337";
    EXPECT_NE(compare_reports(a, b), "");
    b = a;
    b[1] = "    Max skewness = 0.04355001785488 OK.";
    EXPECT_EQ(compare_reports(a, b), "");
}

TEST(CheckMeshOracle, curved_block_hex_mesh)
{
    REQUIRE_OPENFOAM("blockMesh case with curved edges");
    expect_same_report("curved-block", {});
    expect_same_report("curved-block", all_checks);
}

TEST(CheckMeshOracle, gmsh_tetrahedra)
{
    REQUIRE_OPENFOAM("gmsh tetrahedral mesh");
    expect_same_report("tet-gmsh", all_checks);
}

TEST(CheckMeshOracle, damaged_mesh_exercises_failing_checks)
{
    REQUIRE_OPENFOAM("damaged mesh");
    expect_same_report("damaged", all_checks);
    const test::AppRun ours = run_ours(test::openfoam_case("damaged"), {"-allGeometry"});
    EXPECT_EQ(ours.status, app::exit_checks_failed);
    EXPECT_NE(ours.out.find(" ***Zero or negative cell volume detected."), std::string::npos);
    EXPECT_NE(ours.out.find(" ***Error in face pyramids"), std::string::npos);
}

TEST(CheckMeshOracle, snappy_flange)
{
    REQUIRE_OPENFOAM("snappyHexMesh flange");
    expect_same_report("flange", all_checks);
}

TEST(CheckMeshOracle, snappy_flange_mesh_quality_dict)
{
    REQUIRE_OPENFOAM("snappyHexMesh flange with meshQualityDict");
    const fs::path dir = copy_case("flange", "quality_oracle_flange_meshQuality");
    // The tutorial's meshQualityDict (it #includeEtc's snappyHexMesh's defaults).
    std::ofstream(dir / "system" / "meshQualityDict")
        << "FoamFile { version 2.0; format ascii; class dictionary; object meshQualityDict; }\n"
        << "#includeEtc \"caseDicts/mesh/generation/meshQualityDict.cfg\"\n"
        << "maxNonOrtho 30;\nmaxConcave 40;\nminTwist 0.8;\nminTriangleTwist 0.9;\n"
        << "minFaceFlatness 0.9;\nminDeterminant 0.5;\nminFaceWeight 0.3;\n";
    const std::string theirs = run_checkmesh(dir, " -meshQuality");
    const test::AppRun ours = run_ours(dir, {"-meshQuality"});
    const std::vector<std::string> expected = report_block(theirs);
    ASSERT_GT(expected.size(), 10u) << theirs;
    EXPECT_NE(theirs.find("Checking faces in error"), std::string::npos) << theirs;
    EXPECT_EQ(compare_reports(expected, report_block(ours.out)), "");
}

TEST(CheckMeshOracle, wedge_meshes)
{
    REQUIRE_OPENFOAM("wedge meshes");
    // The wedge lines, the directions and what follows them (aspect ratio, determinant).
    for (const std::string name : {"wedge-block", "wedge-cone", "wedge-dlr"})
    {
        expect_same_report(name, {});
        expect_same_report(name, all_checks);
    }
}

TEST(CheckMeshOracle, wedge_with_edges_leaning_across_fails_alike)
{
    REQUIRE_OPENFOAM("non-aligned wedge edges");
    expect_same_report("wedge-twisted", {"-allGeometry"});
    // The "<<Writing" line of the nonAlignedEdges point set too.
    const fs::path dir = copy_case("wedge-twisted", "quality_oracle_wedge_sets");
    const std::string theirs = run_checkmesh(dir, "");
    const test::AppRun ours = run_ours(dir, {"-writeSets"});
    EXPECT_EQ(ours.status, app::exit_checks_failed) << ours.err;
    EXPECT_NE(theirs.find("to set nonAlignedEdges"), std::string::npos) << theirs;
    EXPECT_EQ(compare_reports(report_block(theirs, true), report_block(ours.out, true)), "");
}

TEST(CheckMeshOracle, cyclic_meshes)
{
    REQUIRE_OPENFOAM("cyclic meshes");
    // Coupled faces in non-orthogonality, skewness, weights, volume ratio, the determinant
    // (the column's cells have only two internal faces) and the coupled point match.
    for (const std::string name : {"cyclic-box", "cyclic-column"})
    {
        expect_same_report(name, {});
        expect_same_report(name, all_checks);
    }
}

TEST(CheckMeshOracle, binary_and_compressed_files)
{
    REQUIRE_OPENFOAM("binary / compressed meshes");
    expect_same_report("curved-block-binary", all_checks);
    expect_same_report("tet-gmsh-binary-gz", all_checks);
    expect_same_report("damaged-ascii-gz", {"-allGeometry"});
}

TEST(CheckMeshOracle, written_sets_match_checkmesh_sets)
{
    REQUIRE_OPENFOAM("set files");
    const fs::path dir = copy_case("damaged", "quality_oracle_sets");
    const std::string theirs = run_checkmesh(dir, "-allGeometry");
    // checkMesh wrote its sets; keep them aside, then write ours in their place.
    const fs::path sets = dir / "constant" / "polyMesh" / "sets";
    ASSERT_TRUE(fs::exists(sets)) << theirs;
    const fs::path openfoam_sets = dir / "openfoam_sets";
    fs::rename(sets, openfoam_sets);
    const test::AppRun ours = run_ours(dir, {"-allGeometry", "-writeSets"});
    ASSERT_EQ(ours.status, app::exit_checks_failed) << ours.err;
    // Same "<<Writing" lines as checkMesh (set names and sizes).
    EXPECT_EQ(compare_reports(report_block(theirs, true), report_block(ours.out, true)), "");
    // OpenFOAM reads our files: foamToVTK -faceSet converts the set we wrote.
    for (const auto& entry : fs::directory_iterator(openfoam_sets))
        EXPECT_TRUE(fs::exists(sets / entry.path().filename()))
            << "checkMesh wrote set " << entry.path().filename() << ", we did not";
    ASSERT_TRUE(fs::exists(sets / "wrongOrientedFaces"));
    const std::string command =
        "cd '" + dir.string() + "' && foamToVTK -faceSet wrongOrientedFaces > log.foamToVTK 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << read_text(dir / "log.foamToVTK");
    const std::string log = read_text(dir / "log.foamToVTK");
    EXPECT_EQ(log.find("FOAM FATAL"), std::string::npos) << log;
    // setsToZones reads every set file we wrote.
    const std::string zones =
        "cd '" + dir.string() + "' && setsToZones -noFlipMap > log.setsToZones 2>&1";
    EXPECT_EQ(std::system(zones.c_str()), 0) << read_text(dir / "log.setsToZones");
}

TEST(CheckMeshOracle, short_edges_and_collapsed_points)
{
    REQUIRE_OPENFOAM("short-edge counting");
    // Two interior points moved to within 1e-9 of a neighbour: edges shorter than 1e-6 of the
    // bounding box, which -allGeometry reports (count of points on short edges).
    const fs::path dir = copy_case("curved-block", "quality_oracle_short_edges");
    io::FoamPolyMesh foam = io::read_poly_mesh(dir);
    PolyMesh& mesh = foam.mesh;
    int moved = 0;
    for (Index f = 0; f < mesh.n_internal_faces() && moved < 2; f += 40)
    {
        const std::span<const Index> face = mesh.faces[f];
        mesh.points.row(face[1]) =
            mesh.points.row(face[0]) + 1e-9 * (mesh.points.row(face[1]) - mesh.points.row(face[0]));
        ++moved;
    }
    io::write_points(mesh.points, foam.points, dir, "constant");
    const std::string theirs = run_checkmesh(dir, "-allGeometry");
    ASSERT_NE(theirs.find("Edges too small"), std::string::npos) << theirs;
    const test::AppRun ours = run_ours(dir, {"-allGeometry"});
    EXPECT_EQ(compare_reports(report_block(theirs), report_block(ours.out)), "");
}

TEST(CheckMeshOracle, one_dimensional_periodic_mesh)
{
    REQUIRE_OPENFOAM("1D periodic mesh");
    // planarPoiseuille: 40 graded cells in one column, cyclic in x, empty in z, a wall and a
    // symmetryPlane: 2 solution directions, determinants and weights across the cyclic.
    expect_same_report("periodic-1d", {});
    expect_same_report("periodic-1d", all_checks);
}

TEST(CheckMeshOracle, split_region_meshes)
{
    REQUIRE_OPENFOAM("splitMeshRegions meshes");
    // multiRegionHeater split by cellZones: each region mesh keeps all 5 cellZones, the 4
    // of the other regions empty (checkMesh's inverted 1e+150 box); the small solid heater
    // fails the determinant check, the fluid topAir passes.
    for (const std::string region : {"heater", "topAir"})
    {
        expect_same_report("split-heater", {"-region", region});
        expect_same_report("split-heater", {"-region", region, "-allGeometry", "-allTopology"});
    }
}

TEST(CheckMeshOracle, ami_mesh_regions_and_their_files)
{
    REQUIRE_OPENFOAM("cyclicAMI mesh");
    // mixerVesselAMI2D: the rotor and the stator touch through a cyclicAMI pair only, which
    // connects no cells: two regions, fully disconnected.
    expect_same_report("ami-mixer", {});
    const fs::path dir = copy_case("ami-mixer", "quality_oracle_ami_files");
    const std::string theirs = run_checkmesh(dir, "-allTopology -allGeometry");
    ASSERT_NE(theirs.find("(fully disconnected)"), std::string::npos) << theirs;
    // checkMesh's files, kept aside; ours written in their place.
    const fs::path sets = dir / "constant" / "polyMesh" / "sets";
    const fs::path cell_to_region = dir / "0" / "cellToRegion";
    ASSERT_TRUE(fs::exists(cell_to_region)) << theirs;
    fs::rename(sets, dir / "openfoam_sets");
    fs::rename(cell_to_region, dir / "openfoam_cellToRegion");
    const test::AppRun ours = run_ours(dir, {"-allTopology", "-allGeometry", "-writeSets"});
    ASSERT_EQ(ours.status, app::exit_ok) << ours.err;
    // The region lines, the sets' lines included; checkMesh's AMI weight lines are the
    // only ones we do not print.
    EXPECT_EQ(compare_reports(without_ami_lines(report_block(theirs, true)),
                              report_block(ours.out, true)),
              "");
    EXPECT_LT(without_ami_lines(report_block(theirs, true)).size(),
              report_block(theirs, true).size())
        << "checkMesh printed no AMI lines:\n"
        << theirs;
    // cellToRegion as checkMesh writes it (a labelList in the checked time, 0/), and the
    // region cellSets with the same cells.
    ASSERT_TRUE(fs::exists(cell_to_region)) << ours.out;
    EXPECT_EQ(after_header(cell_to_region), after_header(dir / "openfoam_cellToRegion"));
    EXPECT_NE(read_text(cell_to_region).find("class       labelList;"), std::string::npos);
    for (const std::string set : {"region0", "region1"})
        EXPECT_EQ(list_file_labels(sets / set, true),
                  list_file_labels(dir / "openfoam_sets" / set, true))
            << set;
}

namespace
{

//! A case with `mesh` in constant/polyMesh, a complete controlDict and the fvSchemes and
//! fvSolution that checkMesh's fvMesh reads.
fs::path write_mesh_case(const std::string& name, const PolyMesh& mesh)
{
    const fs::path dir = test::scratch_dir(name);
    io::write_poly_mesh(mesh, io::default_poly_mesh_files(io::FoamFormat::ascii), dir, "constant");
    fs::create_directories(dir / "system");
    std::ofstream(dir / "system" / "controlDict")
        << "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
        << "application checkMesh;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\n"
        << "endTime 1;\ndeltaT 1;\nwriteControl timeStep;\nwriteInterval 1;\n"
        << "writeFormat ascii;\nwritePrecision 15;\nwriteCompression off;\n"
        << "timeFormat general;\ntimePrecision 6;\nrunTimeModifiable false;\n";
    std::ofstream(dir / "system" / "fvSchemes")
        << "FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }\n"
        << "ddtSchemes { default steadyState; }\ngradSchemes { default Gauss linear; }\n"
        << "divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n"
        << "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n";
    std::ofstream(dir / "system" / "fvSolution")
        << "FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n";
    return dir;
}

} // namespace

TEST(CheckMeshOracle, disconnected_and_point_connected_regions)
{
    REQUIRE_OPENFOAM("split two-cell meshes");
    // Two hexahedra with a boundary face each where they touch (tests/helpers.h): with
    // their own coincident points there, fully disconnected, and the 4 pairs of points 0
    // apart are near points; sharing the points (a baffle), point connected, the 4 shared
    // points in multiRegionPoints.
    for (const bool shared : {false, true})
    {
        const fs::path dir =
            write_mesh_case(shared ? "quality_oracle_baffle_pair" : "quality_oracle_split_pair",
                            test::make_split_pair_mesh(shared));
        const std::string theirs = run_checkmesh(dir, "-allTopology -allGeometry");
        EXPECT_NE(theirs.find(shared ? "(point connected)" : "(fully disconnected)"),
                  std::string::npos)
            << theirs;
        if (!shared)
        {
            EXPECT_NE(theirs.find("to set nearPoints"), std::string::npos) << theirs;
        }
        const fs::path sets = dir / "constant" / "polyMesh" / "sets";
        fs::rename(sets, dir / "openfoam_sets");
        fs::rename(dir / "constant" / "cellToRegion", dir / "openfoam_cellToRegion");
        const test::AppRun ours = run_ours(dir, {"-allTopology", "-allGeometry", "-writeSets"});
        ASSERT_TRUE(ours.status == 0 || ours.status == 1) << ours.err;
        EXPECT_EQ(compare_reports(report_block(theirs, true), report_block(ours.out, true)), "")
            << (shared ? "baffle pair" : "split pair");
        // Every set checkMesh wrote, with the same labels; cellToRegion byte for byte
        // after the header (a short list: "2(0 1)").
        for (const auto& entry : fs::directory_iterator(dir / "openfoam_sets"))
        {
            const fs::path ours_set = sets / entry.path().filename();
            ASSERT_TRUE(fs::exists(ours_set)) << "checkMesh wrote set " << entry.path().filename();
            EXPECT_EQ(list_file_labels(ours_set, true), list_file_labels(entry.path(), true))
                << entry.path().filename();
        }
        EXPECT_EQ(after_header(dir / "constant" / "cellToRegion"),
                  after_header(dir / "openfoam_cellToRegion"));
    }
}
