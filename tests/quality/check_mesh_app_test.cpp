// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the checkMeshQuality application (meshmorph/app/check_mesh_case.h) and of the
// JSON report (meshmorph/quality/quality_json.h) on generated cases written by meshmorph's
// own writer: options, exit codes, set files, JSON keys, meshQualityDict errors.
// No OpenFOAM installation is needed (check_mesh_oracle_test.cpp compares with checkMesh).
#include <gtest/gtest.h>

#include "check_mesh_run.h"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "helpers.h"
#include "meshmorph/app/check_mesh_case.h"
#include "meshmorph/core/config.h"
#include "meshmorph/io/write_poly_mesh.h"
#include "meshmorph/quality/quality_json.h"
#include "meshmorph/quality/quality_summary.h"

namespace fs = std::filesystem;
using namespace meshmorph;

namespace
{

fs::path write_case(const std::string& name, const PolyMesh& mesh)
{
    const fs::path dir = test::scratch_dir(name);
    io::write_poly_mesh(mesh, io::default_poly_mesh_files(io::FoamFormat::ascii), dir, "constant");
    fs::create_directories(dir / "system");
    std::ofstream(dir / "system" / "controlDict")
        << "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
        << "writePrecision 10;\n";
    return dir;
}

std::string read_text(const fs::path& path)
{
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

PolyMesh damaged_box()
{
    PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    mesh.points.row(1 + 4 * (1 + 4 * 1)) = Eigen::RowVector3d(0.9, 0.9, 0.9);
    return mesh;
}

} // namespace

TEST(CheckMeshQualityApp, good_mesh_exits_0_and_writes_json)
{
    const fs::path dir = write_case("app_good", test::make_box_mesh(4, 3, 2));
    const test::AppRun r = test::run_check_mesh_quality(
        {"-case", dir.string(), "-allGeometry", "-json", (dir / "q.json").string()});
    ASSERT_EQ(r.status, app::exit_ok) << r.err;
    EXPECT_NE(r.out.find("Time = constant\n\nMesh stats\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\nMesh OK.\n"), std::string::npos);
    EXPECT_NE(r.out.find("\nEnd\n"), std::string::npos);
    const nlohmann::json j = nlohmann::json::parse(read_text(dir / "q.json"));
    EXPECT_EQ(j["cells"], 24);
    EXPECT_EQ(j["cellTypes"]["hexahedra"], 24);
    EXPECT_EQ(j["meshOK"], true);
    EXPECT_EQ(j["failedChecks"], 0);
    EXPECT_DOUBLE_EQ(j["totalVolume"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(j["minScaledJacobian"].get<double>(), 1.0);
    for (const char* key : {"points",
                            "faces",
                            "internalFaces",
                            "patches",
                            "boundingBox",
                            "maxCellOpenness",
                            "maxAspectRatio",
                            "minFaceArea",
                            "maxFaceArea",
                            "minVolume",
                            "maxVolume",
                            "negativeVolumeCells",
                            "maxNonOrthogonality",
                            "avgNonOrthogonality",
                            "severelyNonOrthogonalFaces",
                            "nonOrthogonalityErrors",
                            "incorrectlyOrientedFacePyramids",
                            "maxSkewness",
                            "highlySkewedFaces",
                            "minFaceWeight",
                            "minVolumeRatio",
                            "smallDeterminantCells",
                            "concaveCells",
                            "warpedFaces",
                            "faceTetErrors"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_FALSE(j.contains("meshQualityFailures"));
}

TEST(CheckMeshQualityApp, damaged_mesh_exits_1_and_writes_openfoam_sets)
{
    const fs::path dir = write_case("app_damaged", damaged_box());
    const test::AppRun r =
        test::run_check_mesh_quality({"-case", dir.string(), "-allGeometry", "-writeSets"});
    ASSERT_EQ(r.status, app::exit_checks_failed) << r.err;
    EXPECT_NE(r.out.find("  <<Writing "), std::string::npos);
    const fs::path set = dir / "constant" / "polyMesh" / "sets" / "zeroVolumeCells";
    ASSERT_TRUE(fs::exists(set));
    const std::string text = read_text(set);
    EXPECT_NE(text.find("class       cellSet;"), std::string::npos);
    EXPECT_NE(text.find("location    \"constant/polyMesh/sets\";"), std::string::npos);
    EXPECT_NE(text.find("object      zeroVolumeCells;"), std::string::npos);
    // The line printed for the set names its size, which is the list size in the file.
    const std::string marker = "  <<Writing ";
    const std::size_t at = r.out.find(" zero volume cells to set zeroVolumeCells");
    ASSERT_NE(at, std::string::npos);
    const std::size_t begin = r.out.rfind(marker, at) + marker.size();
    const std::string count = r.out.substr(begin, at - begin);
    EXPECT_NE(text.find("\n" + count + "\n(\n"), std::string::npos) << text;
}

TEST(CheckMeshQualityApp, region_option_reads_and_writes_the_regions_directories)
{
    // A multi-region case (chtMultiRegion layout): constant/solid/polyMesh,
    // system/solid/meshQualityDict, sets to constant/solid/polyMesh/sets.
    const fs::path dir = test::scratch_dir("app_region");
    io::write_poly_mesh(damaged_box(), io::default_poly_mesh_files(io::FoamFormat::ascii), dir,
                        "constant", "solid");
    fs::create_directories(dir / "system" / "solid");
    std::ofstream(dir / "system" / "controlDict")
        << "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n";
    std::ofstream(dir / "system" / "solid" / "meshQualityDict")
        << "FoamFile { version 2.0; format ascii; class dictionary; object meshQualityDict; }\n"
        << "maxNonOrtho 65;\nmaxBoundarySkewness 20;\nmaxInternalSkewness 4;\n"
        << "maxConcave 80;\nminVol 1e-13;\nminTetQuality 1e-15;\nminArea -1;\n"
        << "minTwist 0.02;\nminDeterminant 0.001;\nminFaceWeight 0.05;\nminVolRatio 0.01;\n"
        << "minTriangleTwist -1;\n";
    const test::AppRun r =
        test::run_check_mesh_quality({"-case", dir.string(), "-region", "solid", "-writeSets",
                                      "-meshQuality", "-json", (dir / "q.json").string()});
    ASSERT_EQ(r.status, app::exit_checks_failed) << r.err;
    const fs::path set = dir / "constant/solid/polyMesh/sets/zeroVolumeCells";
    ASSERT_TRUE(fs::exists(set)) << r.out;
    EXPECT_NE(read_text(set).find("location    \"constant/solid/polyMesh/sets\";"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "constant/polyMesh"));
    EXPECT_NE(read_text(dir / "q.json").find("\"region\": \"solid\""), std::string::npos);

    const test::AppRun missing =
        test::run_check_mesh_quality({"-case", dir.string(), "-region", "fluid"});
    EXPECT_EQ(missing.status, app::exit_input_error);
    EXPECT_NE(missing.err.find("constant/fluid/polyMesh"), std::string::npos) << missing.err;
    const test::AppRun bad =
        test::run_check_mesh_quality({"-case", dir.string(), "-region", "../solid"});
    EXPECT_EQ(bad.status, app::exit_input_error);
    EXPECT_NE(bad.err.find("-region"), std::string::npos) << bad.err;
}

TEST(CheckMeshQualityApp, without_write_sets_nothing_is_written)
{
    const fs::path dir = write_case("app_nosets", damaged_box());
    const test::AppRun r = test::run_check_mesh_quality({"-case", dir.string()});
    EXPECT_EQ(r.status, app::exit_checks_failed);
    EXPECT_EQ(r.out.find("<<Writing"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "constant" / "polyMesh" / "sets"));
}

TEST(CheckMeshQualityApp, regions_write_cell_to_region_in_the_checked_time)
{
    // Two cells that share no face: two regions. checkMesh writes <time>/cellToRegion (with
    // -region, <time>/<region>/cellToRegion); we do with -writeSets, as the sets.
    const fs::path dir = write_case("app_regions", test::make_split_pair_mesh(false));
    test::AppRun r = test::run_check_mesh_quality({"-case", dir.string()});
    EXPECT_EQ(r.status, app::exit_ok) << r.err;
    EXPECT_FALSE(fs::exists(dir / "constant" / "cellToRegion"));
    r = test::run_check_mesh_quality({"-case", dir.string(), "-writeSets"});
    EXPECT_EQ(r.status, app::exit_ok) << r.err;
    EXPECT_NE(r.out.find("  <<Writing region information to \"constant/cellToRegion\"\n"),
              std::string::npos)
        << r.out;
    const std::string text = read_text(dir / "constant" / "cellToRegion");
    EXPECT_NE(text.find("class       labelList;"), std::string::npos);
    EXPECT_NE(text.find("location    \"constant\";"), std::string::npos);
    EXPECT_NE(text.find("\n2(0 1)\n"), std::string::npos) << text;
    for (const std::string set : {"region0", "region1"})
        EXPECT_TRUE(fs::exists(dir / "constant" / "polyMesh" / "sets" / set)) << set;

    // A time directory with the mesh: that is the checked time.
    const fs::path timed = test::scratch_dir("app_regions_time");
    io::write_poly_mesh(test::make_split_pair_mesh(false),
                        io::default_poly_mesh_files(io::FoamFormat::ascii), timed, "constant",
                        "solid");
    fs::create_directories(timed / "0");
    fs::create_directories(timed / "system");
    std::ofstream(timed / "system" / "controlDict")
        << "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n";
    r = test::run_check_mesh_quality({"-case", timed.string(), "-region", "solid", "-writeSets"});
    EXPECT_EQ(r.status, app::exit_ok) << r.err;
    EXPECT_NE(r.out.find("Time = 0\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"0/cellToRegion\""), std::string::npos) << r.out;
    ASSERT_TRUE(fs::exists(timed / "0" / "solid" / "cellToRegion"));
    EXPECT_NE(read_text(timed / "0" / "solid" / "cellToRegion").find("location    \"0/solid\";"),
              std::string::npos);
}

TEST(CheckMeshQualityApp, long_cell_to_region_lists_one_label_a_line)
{
    std::vector<Index> labels(11, 0);
    labels[10] = 1;
    const std::string text = app::cell_to_region_file_text(labels, "constant");
    EXPECT_NE(text.find("\n\n\n11\n(\n0\n0\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\n1\n)\n\n\n// ****"), std::string::npos) << text;
}

TEST(CheckMeshQualityApp, usage_and_input_errors_exit_2)
{
    test::AppRun r = test::run_check_mesh_quality({"-bogus"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("unknown option '-bogus'"), std::string::npos);
    r = test::run_check_mesh_quality({"-case"});
    EXPECT_EQ(r.status, 2);
    r = test::run_check_mesh_quality({"-case", "/nonexistent/case"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("/nonexistent/case"), std::string::npos);
    const fs::path empty = test::scratch_dir("app_empty");
    r = test::run_check_mesh_quality({"-case", empty.string()});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("polyMesh"), std::string::npos) << r.err;
    r = test::run_check_mesh_quality({"-help"});
    EXPECT_EQ(r.status, 0);
    for (const char* option : {"-case", "-time", "-latestTime", "-allGeometry", "-allTopology",
                               "-meshQuality", "-writeSets", "-vtk", "-vtkFile", "-json"})
        EXPECT_NE(r.out.find(option), std::string::npos) << option;
    EXPECT_NE(r.out.find("Exit status"), std::string::npos);
}

TEST(CheckMeshQualityApp, mesh_quality_dict_errors_name_file_and_line)
{
    const fs::path dir = write_case("app_mqd", test::make_box_mesh(2, 2, 2));
    test::AppRun r = test::run_check_mesh_quality({"-case", dir.string(), "-meshQuality"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("meshQualityDict"), std::string::npos) << r.err;
    std::ofstream(dir / "system" / "meshQualityDict")
        << "FoamFile { version 2.0; format ascii; class dictionary; object meshQualityDict; }\n"
        << "maxNonOrtho 65;\nmaxBoundarySkewness 20;\nmaxInternalSkewness 4;\n"
        << "maxConcave 80;\nminVol 1e-13;\nminTetQuality 1e-15;\nminArea -1;\n"
        << "minTwist 0.02;\nminDeterminant 0.001;\nminFaceWeight 0.05;\nminVolRatio 0.01;\n";
    r = test::run_check_mesh_quality({"-case", dir.string(), "-meshQuality"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("minTriangleTwist"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("meshQualityDict:"), std::string::npos) << r.err;
    std::ofstream(dir / "system" / "meshQualityDict", std::ios::app) << "minTriangleTwist -1;\n";
    r = test::run_check_mesh_quality(
        {"-case", dir.string(), "-meshQuality", "-json", (dir / "q.json").string()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("Checking faces in error :\n"), std::string::npos);
    EXPECT_NE(r.out.find("    non-orthogonality > 65  degrees                        : 0\n"),
              std::string::npos)
        << r.out;
    const nlohmann::json j = nlohmann::json::parse(read_text(dir / "q.json"));
    EXPECT_EQ(j["meshQualityFailures"]["maxNonOrtho"], 0);
    // Enabled: all but minArea (-1), minTriangleTwist (-1) and minFaceFlatness (absent).
    EXPECT_EQ(j["meshQualityFailures"].size(), 9u);
    std::ofstream(dir / "system" / "meshQualityDict", std::ios::app) << "minFaceFlatness 1.5;\n";
    r = test::run_check_mesh_quality({"-case", dir.string(), "-meshQuality"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("minFaceFlatness"), std::string::npos) << r.err;
}

TEST(QualitySummary, prints_before_and_after_from_the_reports)
{
    CheckMeshSettings settings;
    const QualityReport before = check_mesh(test::make_box_mesh(2, 2, 2), settings);
    const QualityReport after = check_mesh(damaged_box(), settings);
    std::ostringstream out;
    print_quality_summary(out, &before, &after);
    EXPECT_NE(out.str().find("before"), std::string::npos);
    EXPECT_NE(out.str().find("max non-orthogonality [deg]"), std::string::npos);
    EXPECT_NE(out.str().find("Mesh OK"), std::string::npos);
    EXPECT_NE(out.str().find("mesh checks failed"), std::string::npos);
    EXPECT_FALSE(after.mesh_ok());
    EXPECT_GT(after.negative_volume_cells, 0);
    // The table says what the JSON says: the same numbers, formatted with 6 digits.
    const nlohmann::json j = quality_json(after);
    const std::string negative = std::to_string(j["negativeVolumeCells"].get<long long>());
    EXPECT_NE(out.str().find("negative volume cells          0               " + negative),
              std::string::npos)
        << out.str();
    // One column when only one report is given.
    std::ostringstream only_after;
    print_quality_summary(only_after, nullptr, &after);
    EXPECT_EQ(only_after.str().find("before"), std::string::npos) << only_after.str();
    EXPECT_NE(only_after.str().find("mesh checks failed"), std::string::npos);
}

TEST(CheckMeshQualityApp, vtk_file_has_the_quality_fields)
{
#if MESHMORPH_WITH_VTK
    const fs::path dir = write_case("app_vtk", damaged_box());
    const test::AppRun r = test::run_check_mesh_quality(
        {"-case", dir.string(), "-vtkFile", (dir / "quality.vtu").string()});
    ASSERT_EQ(r.status, app::exit_checks_failed) << r.err;
    const std::string vtu = read_text(dir / "quality.vtu");
    for (const char* field :
         {"nonOrthogonality", "skewness", "aspectRatio", "volume", "determinant", "scaledJacobian"})
        EXPECT_NE(vtu.find("Name=\"" + std::string(field) + "\""), std::string::npos) << field;
    EXPECT_NE(vtu.find("NumberOfCells=\"27\""), std::string::npos);
#else
    GTEST_SKIP() << "built without VTK: -vtk is rejected";
#endif
}
