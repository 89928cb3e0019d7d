// SPDX-License-Identifier: GPL-3.0-or-later
// Integration tests of morphMesh (src/meshmorph/app/morph_mesh.*, run in-process through
// run_morph_mesh): what is written where, exactness at constraints, dictionary errors that
// write nothing, refusal of invalid morphs, JSON, and OpenFOAM's checkMesh on the result.
#include "meshmorph/app/morph_mesh.h"
#include "meshmorph/app/morph_session.h"
#include "meshmorph/app/options.h"

#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "helpers.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/temp_file.h"
#include "meshmorph/io/write_poly_mesh.h"
#include "meshmorph/morph/jump_smoothing_guard.h"
#include "meshmorph/morph/non_ortho_repair.h"
#include "morph_run.h"
#include "shipped_pipe.h"

namespace meshmorph::app
{
namespace
{

namespace fs = std::filesystem;

const char* const dict_header =
    "FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }\n";

using test::write_text;

std::string read_text(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

//! A case with `mesh` in constant/polyMesh and `morph_dict` as system/morphDict.
fs::path make_case(const std::string& name, const PolyMesh& mesh, const std::string& morph_dict,
                   io::FoamFormat format = io::FoamFormat::ascii)
{
    const fs::path dir = test::scratch_dir("morph_mesh/" + name);
    io::write_poly_mesh(mesh, io::default_poly_mesh_files(format), dir, "constant");
    write_text(dir / "system/controlDict",
               "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
               "application morphMesh; startFrom latestTime; startTime 0; stopAt endTime;\n"
               "endTime 1; deltaT 1; writeControl timeStep; writeInterval 1;\n"
               "writePrecision 15;\n");
    write_text(dir / "system/morphDict", std::string(dict_header) + morph_dict);
    // OpenFOAM's checkMesh needs these two to start.
    const fs::path pipe_system = test::pipe_tutorial_dir() / "system";
    for (const char* f : {"fvSchemes", "fvSolution"})
        fs::copy_file(pipe_system / f, dir / "system" / f, fs::copy_options::overwrite_existing);
    return dir;
}

using RunResult = test::MorphRun;

RunResult run(const std::vector<std::string>& args)
{
    return test::run_morph_mesh(args);
}

//! Time directories of a case (names).
std::vector<std::string> times(const fs::path& dir)
{
    std::vector<std::string> out;
    for (const io::TimeDir& t : io::list_times(dir))
        out.push_back(t.name);
    return out;
}

const char* const lift_top = R"(
method rbf;
conflicts last;
boundary
{
    zMax { type translate; vector (0 0 0.05); }
}
)";

TEST(MorphMesh, writes_only_points_in_the_next_time_and_constraints_are_exact)
{
    const PolyMesh mesh = test::make_box_mesh(6, 5, 4);
    const fs::path dir = make_case("next_time", mesh, lift_top);
    const std::string original = read_text(dir / "constant/polyMesh/points");
    const RunResult r = run({"-case", dir.string()});
    ASSERT_EQ(r.code, 0) << r.err << r.log;
    EXPECT_EQ(read_text(dir / "constant/polyMesh/points"), original) << "input must not change";
    ASSERT_EQ(times(dir), std::vector<std::string>{"1"});
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(dir / "1/polyMesh"))
        files.push_back(e.path().filename().string());
    EXPECT_EQ(files, std::vector<std::string>{"points"}) << "topology stays in constant/";

    const Points moved = io::read_points_file(dir / "1/polyMesh/points");
    ASSERT_EQ(moved.rows(), mesh.n_points());
    const std::vector<char> boundary = boundary_point_mask(mesh);
    const double lift = 0.05;
    for (Index p = 0; p < mesh.n_points(); ++p)
    {
        if (!boundary[p])
            continue;
        const Eigen::RowVector3d d = moved.row(p) - mesh.points.row(p);
        const bool top = mesh.points(p, 2) == 1.0;
        // Prescriptions: top (edges included, rule last) lifted, everything else fixed.
        // Tolerance 1e-9 relative to the lift plus the 17-digit round trip of the file.
        const Eigen::RowVector3d want(0, 0, top ? lift : 0.0);
        EXPECT_LE((d - want).norm(), 1e-9 * lift + 1e-15) << "point " << p;
    }
    EXPECT_NE(r.log.find("Max constraint error"), std::string::npos);
    EXPECT_NE(r.log.find("Step 1: motion 0 -> 1"), std::string::npos) << r.log;
}

TEST(MorphMesh, a_decomposed_case_is_told_its_processor_directories_keep_the_old_mesh)
{
    const PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    const fs::path dir = make_case("decomposed", mesh, lift_top);
    const RunResult plain = run({"-case", dir.string()});
    ASSERT_EQ(plain.code, 0) << plain.err << plain.log;
    EXPECT_EQ(plain.log.find("the case is decomposed"), std::string::npos) << plain.log;
    fs::create_directories(dir / "processor0/constant/polyMesh");
    fs::create_directories(dir / "processor1/constant/polyMesh");
    const RunResult r = run({"-case", dir.string()});
    ASSERT_EQ(r.code, 0) << r.err << r.log;
    EXPECT_NE(r.log.find("the case is decomposed (processor0 ... processor1)"), std::string::npos)
        << r.log;
    EXPECT_NE(r.log.find("still hold the old mesh"), std::string::npos) << r.log;
}

TEST(MorphMesh, region_option_morphs_that_region_and_writes_its_time_directory)
{
    // chtMultiRegion layout: constant/solid/polyMesh, system/solid/morphDict; the morphed
    // points go to 1/solid/polyMesh/points, which OpenFOAM's checkMesh -region reads.
    const PolyMesh mesh = test::make_box_mesh(4, 4, 4);
    const fs::path dir = make_case("region", mesh, lift_top);
    fs::remove_all(dir / "constant/polyMesh");
    io::write_poly_mesh(mesh, io::default_poly_mesh_files(io::FoamFormat::ascii), dir, "constant",
                        "solid");
    fs::create_directories(dir / "system/solid");
    fs::rename(dir / "system/morphDict", dir / "system/solid/morphDict");
    for (const char* f : {"fvSchemes", "fvSolution"})
        fs::copy_file(dir / "system" / f, dir / "system/solid" / f);
    const RunResult r =
        run({"-case", dir.string(), "-region", "solid", "-json", (dir / "m.json").string()});
    ASSERT_EQ(r.code, 0) << r.err << r.log;
    ASSERT_TRUE(fs::exists(dir / "1/solid/polyMesh/points"));
    EXPECT_FALSE(fs::exists(dir / "1/polyMesh"));
    const Points moved = io::read_points_file(dir / "1/solid/polyMesh/points");
    EXPECT_NEAR((moved - mesh.points).col(2).maxCoeff(), 0.05, 1e-12);
    EXPECT_NE(read_text(dir / "m.json").find("\"region\": \"solid\""), std::string::npos);
    if (test::openfoam_available())
    {
        const std::string cmd =
            "cd '" + dir.string() + "' && checkMesh -region solid -time 1 > log.checkMesh 2>&1";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << read_text(dir / "log.checkMesh");
        EXPECT_NE(read_text(dir / "log.checkMesh").find("Mesh OK."), std::string::npos)
            << read_text(dir / "log.checkMesh");
    }
    const RunResult missing = run({"-case", dir.string()});
    EXPECT_EQ(missing.code, exit_input_error);
    EXPECT_NE(missing.err.find("system/morphDict"), std::string::npos) << missing.err;
}

TEST(MorphMesh, helper_entries_and_included_design_values_drive_the_morph)
{
    // The OpenFOAM idiom for parameter studies: design values in an included file and
    // helper entries at the top level, used as $variables. An unused unknown entry is
    // still an error (a typo must not pass silently).
    const fs::path dir = make_case("helpers", test::make_box_mesh(3, 3, 3), R"(
#include "designValues"
lift    $height;
method  rbf;
conflicts last;
boundary
{
    zMax { type translate; vector (0 0 $lift); }
}
)");
    write_text(dir / "system/designValues", "height 0.04;\n");
    const RunResult r = run({"-case", dir.string()});
    ASSERT_EQ(r.code, 0) << r.err << r.log;
    const Points moved = io::read_points_file(dir / "1/polyMesh/points");
    const PolyMesh mesh = test::make_box_mesh(3, 3, 3);
    EXPECT_NEAR((moved - mesh.points).col(2).maxCoeff(), 0.04, 1e-12);

    write_text(dir / "system/morphDict", std::string(dict_header) + "metod rbf;\nboundary {}\n");
    const RunResult typo = run({"-case", dir.string()});
    EXPECT_EQ(typo.code, exit_input_error);
    EXPECT_NE(typo.err.find("morphDict:2"), std::string::npos) << typo.err;
    EXPECT_NE(typo.err.find("unknown keyword"), std::string::npos) << typo.err;
    EXPECT_NE(typo.err.find("$metod"), std::string::npos) << typo.err;
}

TEST(MorphMesh, overwrite_replaces_points_in_place_keeping_binary_format)
{
    const PolyMesh mesh = test::make_box_mesh(4, 4, 4);
    const fs::path dir = make_case("overwrite_binary", mesh, lift_top, io::FoamFormat::binary);
    const RunResult r = run({"-case", dir.string(), "-overwrite"});
    ASSERT_EQ(r.code, 0) << r.err << r.log;
    EXPECT_TRUE(times(dir).empty()) << "-overwrite writes no time directory";
    io::FoamFileInfo info;
    const Points moved = io::read_points_file(dir / "constant/polyMesh/points", &info);
    EXPECT_TRUE(info.header.is_binary());
    EXPECT_GT((moved - mesh.points).cwiseAbs().maxCoeff(), 0.01);
}

TEST(MorphMesh, overwrite_keeps_the_original_points_and_reruns_say_what_they_replace)
{
    const fs::path dir = make_case("overwrite_orig", test::make_box_mesh(3, 3, 3), lift_top);
    const std::string original = read_text(dir / "constant/polyMesh/points");
    const RunResult first = run({"-case", dir.string(), "-overwrite"});
    ASSERT_EQ(first.code, 0) << first.err;
    EXPECT_EQ(read_text(dir / "constant/polyMesh/points.orig"), original) << "byte for byte";
    EXPECT_NE(first.log.find("points.orig"), std::string::npos) << first.log;
    // A default re-run would morph the morphed points: refused, saying how to ask for either.
    const RunResult refused = run({"-case", dir.string(), "-overwrite"});
    EXPECT_EQ(refused.code, exit_input_error) << refused.err;
    EXPECT_NE(refused.err.find("-time constant"), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("points.orig"), std::string::npos) << refused.err;
    // Asked for by name, the morph builds on it and says so.
    const RunResult second = run({"-case", dir.string(), "-overwrite", "-time", "constant"});
    ASSERT_EQ(second.code, 0) << second.err;
    EXPECT_EQ(read_text(dir / "constant/polyMesh/points.orig"), original) << "kept, not replaced";
    EXPECT_NE(second.log.find("was morphed before"), std::string::npos) << second.log;

    const fs::path fresh = make_case("rerun", test::make_box_mesh(3, 3, 3), lift_top);
    // The same morph again at time 0 (mesh in constant/, fields in 0/): both write 1/.
    fs::create_directories(fresh / "0");
    ASSERT_EQ(run({"-case", fresh.string(), "-time", "0"}).code, 0);
    const RunResult again = run({"-case", fresh.string(), "-time", "0"});
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_NE(again.log.find("replacing"), std::string::npos) << again.log;
}

TEST(MorphMesh, the_same_command_twice_writes_the_same_mesh)
{
    // As windAroundBuildings is after snappyHexMesh: no 0/ (fields in 0.orig),
    // `startFrom latestTime`. The second run reads what the first read (constant), not the
    // first one's result in 1/, and writes the same points to the same time.
    const fs::path dir = make_case("rerun_no_zero", test::make_box_mesh(3, 3, 3), lift_top);
    fs::create_directories(dir / "0.orig");
    ASSERT_EQ(run({"-case", dir.string()}).code, 0);
    const std::string first = read_text(dir / "1/polyMesh/points");
    EXPECT_NE(first.find("morphed by morphMesh from the points of constant"), std::string::npos)
        << "a morph's result says so in its header";
    const RunResult again = run({"-case", dir.string()});
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_NE(again.log.find("constant/polyMesh"), std::string::npos) << again.log;
    EXPECT_EQ(times(dir), std::vector<std::string>{"1"});
    EXPECT_EQ(read_text(dir / "1/polyMesh/points"), first) << "the re-run added to the morph";

    // Building on a result is asked for by name: -latestTime reads 1/ and writes 2/.
    const RunResult on_top = run({"-case", dir.string(), "-latestTime"});
    ASSERT_EQ(on_top.code, 0) << on_top.err;
    EXPECT_EQ((std::vector<std::string>{"1", "2"}), times(dir));
    const Points once = io::read_points_file(dir / "1/polyMesh/points");
    const Points twice = io::read_points_file(dir / "2/polyMesh/points");
    EXPECT_GT((twice - once).cwiseAbs().maxCoeff(), 0.04) << "the top lifted again";
    EXPECT_NE(read_text(dir / "2/polyMesh/points").find("the points of 1"), std::string::npos);
    // And a default run still starts from constant/, writing 1/ again.
    ASSERT_EQ(run({"-case", dir.string()}).code, 0);
    EXPECT_EQ(read_text(dir / "1/polyMesh/points"), first);
}

TEST(MorphMesh, an_overflowing_or_non_finite_motion_is_an_error_naming_the_entry)
{
    // 1e300 used to give non-finite points written as "Mesh OK"; 1e20 an internal error.
    for (const char* size : {"1e300", "1e200", "1e100", "1e20"})
    {
        const fs::path dir =
            make_case(std::string("overflow_") + size, test::make_box_mesh(3, 3, 3),
                      "boundary\n{\n    zMax { type translate; vector (0 " + std::string(size) +
                          " 0); }\n}\n");
        const RunResult r = run({"-case", dir.string(), "-json", (dir / "r.json").string()});
        EXPECT_EQ(r.code, exit_input_error) << size << r.log << r.err;
        EXPECT_NE(r.err.find("morphDict:4"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("zMax"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("times the mesh's size"), std::string::npos) << r.err;
        EXPECT_TRUE(times(dir).empty()) << "nothing written";
        EXPECT_FALSE(nlohmann::json::parse(read_text(dir / "r.json"))["written"].get<bool>());
    }
}

TEST(MorphMesh, motion_normal_to_a_2d_case_planes_is_an_error_naming_the_entry)
{
    // A one-cell-thick box whose z faces are empty: moving a wall along z used to be
    // dropped silently, writing unchanged points with exit 0.
    PolyMesh mesh = test::make_box_mesh(4, 4, 1);
    for (Patch& p : mesh.patches)
        if (p.name == "zMin" || p.name == "zMax")
            p.type = "empty";
    const std::vector<std::pair<std::string, std::string>> refused = {
        {"translate; vector (0 0 0.01);", "remove its component along the normal"},
        {"translate; vector (0.01 0 0.01);", "remove its component along the normal"},
        {"rotate; origin (0 0 0); axis (1 0 0); angle 3;", "axis parallel to the normal"},
        {"scale; origin (0 0 -1); factor (1.1 1.1 1.1);", "factor 1 along the normal"}};
    for (const auto& [motion, hint] : refused)
    {
        const fs::path dir =
            make_case("normal_2d", mesh, "boundary\n{\n    xMax { type " + motion + " }\n}\n");
        const RunResult r = run({"-case", dir.string()});
        EXPECT_EQ(r.code, exit_input_error) << motion << r.log << r.err;
        EXPECT_NE(r.err.find("morphDict:4: boundary entry 'xMax'"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("2D case"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(hint), std::string::npos) << r.err;
        EXPECT_TRUE(times(dir).empty()) << motion;
    }
    // In-plane motions of the same case morph as before.
    for (const char* motion :
         {"translate; vector (0.01 0.02 0);", "rotate; origin (0.5 0.5 7); axis (0 0 1); angle 3;",
          "scale; origin (0.5 0.5 7); factor (1.05 1.1 1);"})
    {
        const fs::path dir = make_case(
            "in_plane_2d", mesh, std::string("boundary\n{\n    xMax { type ") + motion + " }\n}\n");
        const RunResult r = run({"-case", dir.string()});
        EXPECT_EQ(r.code, 0) << motion << r.log << r.err;
    }
}

TEST(MorphMesh, a_morph_that_bends_a_symmetry_plane_is_refused_naming_the_patch)
{
    // OpenFOAM refuses to read a mesh whose symmetryPlane patch is not planar ("Symmetry
    // plane 'zMin' is not planar"), so a morph that bends one must not be written as fit:
    // with `conflicts last` the scaled xMax takes the points it shares with zMin off z = 0.
    PolyMesh mesh = test::make_box_mesh(4, 4, 4);
    for (Patch& p : mesh.patches)
        if (p.name == "zMin")
            p.type = "symmetryPlane";
    const std::string scale_x_max = R"(
boundary
{
    xMax { type scale; origin (0.5 0.5 0.5); factor (1.1 1.1 1.1); }
}
)";
    const fs::path bent = make_case("bent_symmetry", mesh, "conflicts last;\n" + scale_x_max);
    const RunResult r = run({"-case", bent.string(), "-json", (bent / "r.json").string()});
    EXPECT_EQ(r.code, exit_refused) << r.log;
    // OpenFOAM compares each face's normal with the patch's average normal: the 4 faces
    // beside xMax tilt, and the average tilts with them, so all 16 faces are off it.
    EXPECT_NE(r.err.find("the morph bends symmetryPlane 'zMin' (16 faces"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("conflicts fixed;"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("reduce the motion"), std::string::npos) << "not the remedy: " << r.err;
    EXPECT_TRUE(times(bent).empty()) << "nothing written";
    const nlohmann::json j = nlohmann::json::parse(read_text(bent / "r.json"));
    EXPECT_EQ(j["bentSymmetryPlanes"], nlohmann::json({{"zMin", 16}})) << j.dump();
    if (test::openfoam_available()) // the oracle: OpenFOAM cannot read what -force writes
    {
        ASSERT_EQ(run({"-case", bent.string(), "-force"}).code, 0);
        const std::string cmd =
            "cd '" + bent.string() + "' && checkMesh -latestTime > log.checkMesh 2>&1";
        EXPECT_NE(std::system(cmd.c_str()), 0);
        EXPECT_NE(read_text(bent / "log.checkMesh").find("Symmetry plane 'zMin' is not planar"),
                  std::string::npos)
            << read_text(bent / "log.checkMesh");
    }

    // The default rule holds the shared points still: the plane stays a plane.
    const fs::path kept = make_case("kept_symmetry", mesh, scale_x_max);
    const RunResult k = run({"-case", kept.string(), "-json", (kept / "r.json").string()});
    ASSERT_EQ(k.code, 0) << k.log;
    EXPECT_EQ(nlohmann::json::parse(read_text(kept / "r.json"))["bentSymmetryPlanes"],
              nlohmann::json::object());
    if (test::openfoam_available())
    {
        const std::string cmd =
            "cd '" + kept.string() + "' && checkMesh -latestTime > log.checkMesh 2>&1";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << read_text(kept / "log.checkMesh");
    }
}

TEST(MorphMesh, a_check_the_morph_makes_fail_is_a_warning_or_on_request_an_error)
{
    // The whole box flattened 2000 times (an affine map, which the RBF's linear part
    // reproduces exactly: no cell inverts) fails checkMesh's aspect ratio (above 1000).
    const std::string flatten =
        "boundary\n{\n    \".*\" { type scale; origin (0 0 0); factor (1 1 0.0005); }\n}\n";
    const fs::path dir = make_case("new_failure", test::make_box_mesh(3, 3, 3), flatten);
    const RunResult r = run({"-case", dir.string(), "-json", (dir / "r.json").string()});
    ASSERT_EQ(r.code, 0) << r.err << r.log;
    EXPECT_NE(r.err.find("Warning"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("fails the check aspectRatio (27 offenders)"), std::string::npos) << r.err;
    const nlohmann::json j = nlohmann::json::parse(read_text(dir / "r.json"));
    ASSERT_EQ(j["newFailedChecks"].size(), 1u) << j.dump();
    EXPECT_EQ(j["newFailedChecks"][0]["check"], "aspectRatio");
    EXPECT_EQ(j["newFailedChecks"][0]["count"].get<int>(), 27);

    // A script makes it an error: refused, nothing written.
    const fs::path strict = make_case("new_failure_refused", test::make_box_mesh(3, 3, 3),
                                      "newCheckFailures refuse;\n" + flatten);
    const RunResult refused = run({"-case", strict.string()});
    EXPECT_EQ(refused.code, exit_refused) << refused.err;
    EXPECT_NE(refused.err.find("aspectRatio"), std::string::npos) << refused.err;
    EXPECT_TRUE(times(strict).empty());
    // A morph that fails nothing new has the key, empty.
    const fs::path fine = make_case("no_new_failure", test::make_box_mesh(3, 3, 3), lift_top);
    ASSERT_EQ(run({"-case", fine.string(), "-json", (fine / "r.json").string()}).code, 0);
    EXPECT_TRUE(nlohmann::json::parse(read_text(fine / "r.json"))["newFailedChecks"].empty());
}

TEST(MorphMesh, a_region_the_case_does_not_have_is_named_as_such)
{
    const fs::path dir = make_case("no_region", test::make_box_mesh(2, 2, 2), lift_top);
    const RunResult r = run({"-case", dir.string(), "-region", "fluid"});
    EXPECT_EQ(r.code, exit_input_error);
    EXPECT_NE(r.err.find("-region fluid: the case has no such region"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("single-region case"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("morphDict"), std::string::npos) << "not a missing dictionary: " << r.err;
}

//! An annular sector about the x axis between wedge patches zMin and zMax, `degrees` wide:
//! x in [0, 1], radius in [0.5, 1] (walls yMin, yMax), inlet xMin, outlet xMax.
PolyMesh annular_wedge(double degrees)
{
    const double angle = degrees * std::numbers::pi / 180.0;
    return test::make_block_mesh(12, 6, 1,
                                 [&](double u, double v, double w)
                                 {
                                     const double r = 0.5 + 0.5 * v, phi = (w - 0.5) * angle;
                                     return Vector3(u, r * std::cos(phi), r * std::sin(phi));
                                 },
                                 {"patch", "patch", "wall", "wall", "wedge", "wedge"});
}

TEST(MorphMesh, jump_smoothing_yes_in_a_wedge_case_is_refused_naming_the_key)
{
    // The band's Laplacian would not keep the two wedge planes rotations of each other:
    // `yes` is refused by name and nothing is written (`auto` leaves wedges unsmoothed).
    const fs::path dir = make_case("wedge_jump_smoothing", annular_wedge(5.0),
                                   "jumpSmoothing yes;\nboundary\n{\n"
                                   "    yMax { type translate; vector (0.05 0 0); }\n}\n");
    const RunResult r = run({"-case", dir.string()});
    EXPECT_EQ(r.code, exit_input_error) << r.log;
    EXPECT_NE(r.err.find("'jumpSmoothing yes;'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("wedge"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "1")) << "nothing written";
}

TEST(MorphMesh, a_wedge_case_keeps_its_symmetry_exactly)
{
    // The greedy RBF and its IDW correction choose centres point by point, so the two
    // wedge planes got displacements that differed by ~1e-3 of the motion, and checkMesh
    // failed edge alignment (biconic25-55Run35, a 0.1 degree wedge). Each point of one plane
    // must move as the rotation of its partner's motion, within its plane.
    for (const double degrees : {5.0, 0.1})
    {
        const PolyMesh mesh = annular_wedge(degrees);
        const fs::path dir =
            make_case("wedge_" + std::to_string(int(degrees * 10)), mesh,
                      "rbf { greedy { tolerance 1e-2; } }\nboundary\n{\n"
                      "    yMax { type translate; vector (0.05 0 0); }\n"
                      "    xMax { type scale; origin (0 0 0); factor (1.02 1.02 1.02); }\n}\n");
        const RunResult r = run({"-case", dir.string(), "-json", (dir / "r.json").string()});
        ASSERT_EQ(r.code, 0) << r.err << r.log;
        const Points moved = io::read_points_file(dir / "1/polyMesh/points");
        const double angle = degrees * std::numbers::pi / 180.0;
        const Eigen::Matrix3d back_to_front =
            Eigen::AngleAxisd(angle, Vector3::UnitX()).toRotationMatrix();
        const Vector3 back_normal(0, std::sin(-angle / 2), -std::cos(-angle / 2));
        double asymmetry = 0, off_plane = 0, largest = 0;
        const Index per_plane = 13 * 7; // points of the 12 x 6 block's k = 0 plane
        for (Index p = 0; p < per_plane; ++p)
        {
            const Vector3 back = (moved.row(p) - mesh.points.row(p)).transpose();
            const Vector3 front =
                (moved.row(p + per_plane) - mesh.points.row(p + per_plane)).transpose();
            asymmetry = std::max(asymmetry, (back_to_front * back - front).norm());
            off_plane = std::max(off_plane, std::abs(back.dot(back_normal)));
            largest = std::max(largest, back.norm());
        }
        ASSERT_GT(largest, 0.04) << "the wall moved";
        // 1e-12 of the motion: far below any checkMesh tolerance, above the 15 digits of
        // the written points.
        EXPECT_LE(asymmetry, 1e-12 * largest) << degrees << " degrees";
        EXPECT_LE(off_plane, 1e-12 * largest) << degrees << " degrees";
        const nlohmann::json j = nlohmann::json::parse(read_text(dir / "r.json"));
        EXPECT_EQ(j["after"]["failedChecks"].get<int>(), 0) << j["after"].dump();
        EXPECT_TRUE(j["newFailedChecks"].empty()) << j["newFailedChecks"].dump();
    }
    // A motion that is not axisymmetric cannot be followed: an error naming the entry (it
    // used to be a conflict with the wedge planes, the points held by rule 'fixed').
    for (const char* motion :
         {"translate; vector (0 0.05 0);", "rotate; origin (0.5 0 0); axis (0 0 1); angle 2;"})
    {
        const fs::path dir =
            make_case("wedge_asymmetric", annular_wedge(5.0),
                      std::string("boundary\n{\n    yMax { type ") + motion + " }\n}\n");
        const RunResult r = run({"-case", dir.string()});
        EXPECT_EQ(r.code, exit_input_error) << motion << r.log;
        EXPECT_NE(r.err.find("boundary entry 'yMax'"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("axisymmetric case"), std::string::npos) << r.err;
    }
}

TEST(MorphMesh, the_sensitivity_of_a_smoothed_morph_equals_central_differences)
{
    // The lid lifted against fixed sides with the band smoothed: dJ/dXs carries dJ/dx at
    // the band's points back through the Laplacian to the points it reads. For J = g . x and
    // the lift scaled by 1 +- 1% (the morph is linear in it with its choices held: the
    // greedy centres, the jump band), central differences equal the sum of dJ/dXs . dlift.
    const std::string lid = "boundary { zMax { type translate; vector (0 0 LIFT); } }\n";
    const auto with_lift = [&](const char* lift)
    { return std::regex_replace(lid, std::regex("LIFT"), lift); };
    // The repair of faces above maxNonOrtho is not differentiated (the sensitivity warns):
    // off, so that the morph is the smoothed field alone.
    const std::string keys = "jumpSmoothing yes;\nmaxNonOrtho none;\n";
    const fs::path dir =
        make_case("smoothed_sensitivity", test::make_box_mesh(24, 24, 12), keys + with_lift("0.2"));
    for (const char* lift : {"0.202", "0.198"})
        write_text(dir / "system" / (std::string("morphDict.") + lift),
                   std::string(dict_header) + keys + with_lift(lift));
    morph::MorphOptions options;
    options.case_dir = dir;
    app::MorphSession session(options);
    ASSERT_GT(session.morph().steps.back().jump_smoothed_points, 0);
    ASSERT_EQ(session.result().steps.size(), 1u);
    std::srand(11);
    const Points g = Points::Random(session.mesh().n_points(), 3);
    const Points sensitivity = session.sensitivity(g);
    const auto objective = [&](const char* lift)
    {
        session.reset();
        session.morph(dir / "system" / (std::string("morphDict.") + lift));
        return (g.array() * session.points().array()).sum();
    };
    const double central = (objective("0.202") - objective("0.198")) / 2.0;
    // The lid's points off its rim (the rim is held: conflicts fixed) take the lift.
    const Points& x = session.initial_points();
    const Vector3 lo = x.colwise().minCoeff(), hi = x.colwise().maxCoeff();
    double predicted = 0.0;
    for (Index p = 0; p < x.rows(); ++p)
        if (x(p, 2) == hi.z() && x(p, 0) > lo.x() && x(p, 0) < hi.x() && x(p, 1) > lo.y() &&
            x(p, 1) < hi.y())
            predicted += 0.002 * sensitivity(p, 2);
    EXPECT_NEAR(central, predicted, 1e-8 * std::abs(predicted));
}

TEST(MorphMesh, jump_smoothing_auto_keeps_the_smoothed_band_only_where_it_is_better)
{
    // The lid lifted against fixed sides (conflicts fixed: its edges stay; the band, 0.1
    // wide, spans a cell of 1/12 below the rim): the prescription jumps along the lid's rim.
    // `no` leaves the fitted field, `yes` smooths the band, the default `auto` compares the
    // two on the band's cells and keeps the one with the lower non-orthogonality: its mesh
    // is the better of the two, and every one is exact.
    const std::string lid = "boundary { zMax { type translate; vector (0 0 0.2); } }\n";
    std::map<std::string, nlohmann::json> runs;
    for (const std::string mode : {"no", "yes", "auto", ""})
    {
        const std::string keys = mode.empty() ? "" : "jumpSmoothing " + mode + ";\n";
        const fs::path dir = make_case("jump_smoothing_" + (mode.empty() ? "default" : mode),
                                       test::make_box_mesh(24, 24, 12), keys + lid);
        const RunResult r = run({"-case", dir.string(), "-json", (dir / "morph.json").string()});
        ASSERT_EQ(r.code, 0) << r.err;
        runs[mode] = nlohmann::json::parse(read_text(dir / "morph.json"));
        const nlohmann::json& j = runs[mode];
        EXPECT_EQ(j["jumpSmoothing"], mode.empty() ? "auto" : mode);
        EXPECT_LE(j["maxConstraintError"].get<double>(), 1e-9 * 0.2) << mode;
        EXPECT_EQ(j["after"]["negativeVolumeCells"].get<int>(), 0) << mode;
        if (mode == "auto")
        {
            EXPECT_NE(r.out.find("    jump smoothing "), std::string::npos) << r.out;
        }
    }
    const auto smoothed = [&](const std::string& m)
    { return runs[m]["steps"].back()["jumpSmoothedPoints"].get<int>(); };
    const auto non_ortho = [&](const std::string& m)
    { return runs[m]["after"]["maxNonOrthogonality"].get<double>(); };
    EXPECT_EQ(smoothed("no"), 0);
    EXPECT_GT(smoothed("yes"), 0);
    EXPECT_TRUE(runs["yes"]["steps"].back()["jumpSmoothingChoice"].is_null());
    const nlohmann::json choice = runs["auto"]["steps"].back()["jumpSmoothingChoice"];
    ASSERT_TRUE(choice.is_object());
    const bool kept = choice["kept"].get<bool>();
    const double with = choice["smoothed"]["maxNonOrthogonality"].get<double>();
    const double without = choice["fitted"]["maxNonOrthogonality"].get<double>();
    EXPECT_EQ(kept, with < without - morph::margin_degrees);
    EXPECT_EQ(smoothed("auto"), kept ? smoothed("yes") : 0);
    EXPECT_EQ(non_ortho("auto"), kept ? non_ortho("yes") : non_ortho("no"));
    EXPECT_LE(non_ortho("auto"), std::min(non_ortho("yes"), non_ortho("no")) + 1e-12);
    EXPECT_EQ(runs[""]["after"], runs["auto"]["after"]) << "auto is the default";
}

TEST(MorphMesh, faces_a_morph_takes_above_max_non_ortho_are_repaired_locally)
{
    // The lid lifted against fixed sides (conflicts fixed: its rim stays): the cells under
    // the rim shear past 70 degrees. The default (maxNonOrtho 70) moves interior points near
    // them until none of those faces is above 70 (aiming at 69), leaves every boundary point
    // where the prescription puts it, and says so in the log and the JSON; `none` keeps the
    // fitted field, faces above 70 and all.
    const std::string lid = "boundary { zMax { type translate; vector (0 0 0.2); } }\n";
    std::map<std::string, nlohmann::json> runs;
    for (const std::string keys : {"maxNonOrtho none;\n", ""})
    {
        const fs::path dir = make_case(keys.empty() ? "non_ortho_default" : "non_ortho_none",
                                       test::make_box_mesh(24, 24, 12), keys + lid);
        const RunResult r = run({"-case", dir.string(), "-json", (dir / "morph.json").string()});
        ASSERT_EQ(r.code, 0) << r.err;
        runs[keys] = nlohmann::json::parse(read_text(dir / "morph.json"));
        EXPECT_LE(runs[keys]["maxConstraintError"].get<double>(), 1e-9 * 0.2) << keys;
        EXPECT_EQ(r.out.find("repaired non-orthogonality: ") != std::string::npos, keys.empty())
            << r.out;
    }
    const nlohmann::json& fitted = runs["maxNonOrtho none;\n"];
    const nlohmann::json& repaired = runs[""];
    ASSERT_GT(fitted["after"]["maxNonOrthogonality"].get<double>(), 70.0)
        << "the lift makes faces above 70 without the repair: " << fitted["after"].dump();
    EXPECT_EQ(fitted["steps"].back()["nonOrthRepair"]["cells"].get<int>(), 0);
    const nlohmann::json& step = repaired["steps"].back()["nonOrthRepair"];
    EXPECT_GT(step["cells"].get<int>(), 0) << step.dump();
    EXPECT_GT(step["pointsMoved"].get<int>(), 0) << step.dump();
    EXPECT_EQ(step["stillAbove"].get<int>(), 0) << step.dump();
    EXPECT_LT(repaired["after"]["maxNonOrthogonality"].get<double>(),
              70.0 - 0.5 * morph::non_ortho_margin_degrees);
    EXPECT_EQ(repaired["after"]["negativeVolumeCells"].get<int>(), 0);
    EXPECT_EQ(repaired["after"]["incorrectlyOrientedFacePyramids"].get<int>(), 0);
}

TEST(MorphMesh, max_non_ortho_out_of_range_is_an_error_naming_the_entry)
{
    for (const char* value : {"95", "0", "off70"})
    {
        const fs::path dir = make_case("non_ortho_bad", test::make_box_mesh(3, 3, 3),
                                       std::string("maxNonOrtho ") + value + ";\n" + lift_top);
        const RunResult r = run({"-case", dir.string()});
        EXPECT_EQ(r.code, exit_input_error) << value << r.log;
        EXPECT_NE(r.err.find("maxNonOrtho"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("between 0 and 90"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "1")) << value;
    }
}

TEST(MorphMesh, json_has_the_interface_keys)
{
    const fs::path dir = make_case("json", test::make_box_mesh(3, 3, 3), lift_top);
    const RunResult r = run({"-case", dir.string(), "-json", (dir / "morph.json").string()});
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(read_text(dir / "morph.json"));
    for (const char* key :
         {"method", "constraints", "centres", "maxConstraintError", "timings", "before", "after"})
        EXPECT_TRUE(j.contains(key)) << key;
    for (const char* key : {"read", "fit", "evaluate", "check", "write"})
        EXPECT_TRUE(j["timings"].contains(key)) << key;
    EXPECT_EQ(j["method"], "rbf");
    EXPECT_EQ(j["constraints"].get<int>(), 4 * 4 * 4 - 2 * 2 * 2);
    EXPECT_TRUE(j["after"].contains("maxNonOrthogonality"));
    EXPECT_TRUE(j["before"].contains("negativeVolumeCells"));
    EXPECT_LE(j["maxConstraintError"].get<double>(), 1e-9 * 0.05);
}

TEST(MorphMesh, a_failed_run_replaces_an_earlier_json_report_with_the_error)
{
    const fs::path dir = make_case("json_failure", test::make_box_mesh(3, 3, 3), lift_top);
    const fs::path json = dir / "morph.json";
    ASSERT_EQ(run({"-case", dir.string(), "-json", json.string()}).code, 0);
    EXPECT_TRUE(nlohmann::json::parse(read_text(json))["written"].get<bool>());
    EXPECT_EQ(nlohmann::json::parse(read_text(json))["exitStatus"].get<int>(), 0);
    write_text(dir / "system/morphDict",
               std::string(dict_header) + "boundary { wing { type fixed; } }\n");
    const RunResult r = run({"-case", dir.string(), "-json", json.string()});
    EXPECT_EQ(r.code, exit_input_error);
    const nlohmann::json j = nlohmann::json::parse(read_text(json));
    EXPECT_FALSE(j["written"].get<bool>()) << "no stale success may remain";
    EXPECT_EQ(j["exitStatus"].get<int>(), exit_input_error);
    EXPECT_NE(j["error"].get<std::string>().find("wing"), std::string::npos) << j.dump();
}

TEST(MorphMesh, overwrite_removes_the_temporary_a_killed_run_left_of_points_orig)
{
    const fs::path dir = make_case("stale_orig", test::make_box_mesh(2, 2, 2), lift_top);
    const fs::path mesh_dir = dir / "constant/polyMesh";
    // A run killed after keeping the original (points.orig equal to the points), and one
    // killed while it wrote points.orig: its temporary, named for a process that is gone.
    fs::copy_file(mesh_dir / "points", mesh_dir / "points.orig");
    const pid_t gone = ::fork();
    ASSERT_GE(gone, 0);
    if (gone == 0)
        ::_exit(0);
    ASSERT_EQ(::waitpid(gone, nullptr, 0), gone);
    std::string name = io::temp_path_for(mesh_dir / "points.orig").filename().string();
    const std::string mine = "." + std::to_string(::getpid()) + ".";
    ASSERT_NE(name.find(mine), std::string::npos) << name;
    name.replace(name.find(mine), mine.size(), "." + std::to_string(gone) + ".");
    write_text(mesh_dir / name, "partial");

    const RunResult r = run({"-case", dir.string(), "-overwrite"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_FALSE(fs::exists(mesh_dir / name)) << "the killed run's temporary is left";
    EXPECT_TRUE(fs::exists(mesh_dir / "points.orig"));
}

TEST(MorphMesh, a_morph_that_inverts_cells_is_refused_unless_forced)
{
    // The top pushed through the bottom: cells turn inside out.
    const fs::path dir = make_case("refuse", test::make_box_mesh(3, 3, 3), R"(
conflicts last;
boundary { zMax { type translate; vector (0 0 -1.6); } }
)");
    const RunResult refused = run({"-case", dir.string()});
    EXPECT_EQ(refused.code, exit_refused) << refused.err;
    EXPECT_NE(refused.err.find("negative-volume"), std::string::npos) << refused.err;
    EXPECT_TRUE(times(dir).empty()) << "nothing may be written";

    const RunResult forced = run({"-case", dir.string(), "-force"});
    EXPECT_EQ(forced.code, 0) << forced.err;
    EXPECT_EQ(times(dir), std::vector<std::string>{"1"});
}

struct BadDict
{
    std::string name;
    std::string text;
    std::vector<std::string> expected; //!< substrings of the error message
};

TEST(MorphMesh, every_dictionary_error_names_file_and_entry_and_writes_nothing)
{
    const std::vector<BadDict> cases{
        {"unknown_patch", "boundary { wing { type fixed; } }", {"wing", "no patch"}},
        {"regex_matches_nothing",
         "boundary { \"motorBike_.*\" { type translate; vector (0 0 1); } }",
         {"motorBike_.*", "matches no patch"}},
        {"unknown_type", "boundary { zMax { type glide; } }", {"glide", "zMax"}},
        {"unknown_method", "method spline;", {"spline", "method"}},
        {"missing_key", "boundary { zMax { type translate; } }", {"vector", "zMax"}},
        {"extra_key", "boundary { zMax { type fixed; vector (0 0 1); } }", {"vector", "zMax"}},
        {"syntax_error", "boundary { zMax { type fixed; }", {"morphDict:"}},
        {"bad_vector", "boundary { zMax { type translate; vector (0 0); } }", {"vector"}},
        {"unknown_top_level", "boundry { zMax { type fixed; } }", {"boundry"}},
        {"unreadable_surface",
         "boundary { zMax { type surface; file \"constant/triSurface/nothere.stl\"; } }",
         {"nothere.stl"}},
        {"missing_point_zone",
         "handles { roof { pointZone roofPoints; displacement (0 0 0.1); } }",
         {"roofPoints", "roof"}},
        {"bad_conflict_rule", "conflicts maybe;", {"maybe", "conflicts"}},
        {"bad_jump_smoothing", "jumpSmoothing maybe;", {"maybe", "jumpSmoothing"}},
    };
    for (const BadDict& c : cases)
    {
        const fs::path dir = make_case("bad_" + c.name, test::make_box_mesh(2, 2, 2), c.text);
        const std::string original = read_text(dir / "constant/polyMesh/points");
        const RunResult r = run({"-case", dir.string(), "-json", (dir / "out.json").string()});
        EXPECT_EQ(r.code, exit_input_error) << c.name << ": " << r.err;
        EXPECT_NE(r.err.find((dir / "system/morphDict").string()), std::string::npos)
            << c.name << ": the message must name the file: " << r.err;
        for (const std::string& s : c.expected)
            EXPECT_NE(r.err.find(s), std::string::npos)
                << c.name << ": '" << s << "' not in " << r.err;
        EXPECT_TRUE(times(dir).empty()) << c.name << ": a time directory was written";
        // The report says what failed (issue: a stale success must never remain).
        const nlohmann::json j = nlohmann::json::parse(read_text(dir / "out.json"));
        EXPECT_FALSE(j["written"].get<bool>()) << c.name;
        EXPECT_EQ(j["exitStatus"].get<int>(), exit_input_error) << c.name;
        EXPECT_EQ(read_text(dir / "constant/polyMesh/points"), original) << c.name;
    }
}

TEST(MorphMesh, missing_dictionary_and_bad_options_are_errors)
{
    const fs::path dir = make_case("no_dict", test::make_box_mesh(2, 2, 2), "");
    fs::remove(dir / "system/morphDict");
    RunResult r = run({"-case", dir.string()});
    EXPECT_EQ(r.code, exit_input_error);
    EXPECT_NE(r.err.find("morphDict"), std::string::npos) << r.err;
    r = run({"-case", dir.string(), "-method", "spline"});
    EXPECT_EQ(r.code, exit_input_error);
    r = run({"-case", dir.string(), "-time", "1", "-latestTime"});
    EXPECT_EQ(r.code, exit_input_error);
    EXPECT_TRUE(times(dir).empty());
}

TEST(MorphMesh, dmffd_and_ffd_methods_run_and_report_their_residual)
{
    const fs::path dir =
        make_case("methods", test::make_box_mesh(4, 4, 4), std::string(lift_top) + R"(
dmffd { lattice (6 6 6); clamping 1e-2; }
ffd   { lattice (4 4 4); displacements ( ((1 1 3) (0 0 0.02)) ((2 2 3) (0 0 0.02)) ); }
)");
    for (const std::string method : {"dmffd", "ffd"})
    {
        const RunResult r = run({"-case", dir.string(), "-method", method, "-json",
                                 (dir / (method + ".json")).string()});
        ASSERT_EQ(r.code, 0) << method << r.err;
        const nlohmann::json j = nlohmann::json::parse(read_text(dir / (method + ".json")));
        EXPECT_EQ(j["method"], method);
        // Neither method interpolates: their residual must show up (not be hidden).
        EXPECT_GT(j["maxConstraintError"].get<double>(), 1e-6) << method;
    }
}

TEST(MorphMesh, surface_pointdisplacement_and_handles_from_the_dictionary)
{
    const PolyMesh mesh = test::make_box_mesh(4, 4, 4);
    const fs::path dir = make_case("data_driven", mesh, R"D(
conflicts last;
boundary
{
    default { type fixed; }
    zMax    { type surface; file "constant/triSurface/lid.stl"; }
    yMin    { type pointDisplacement; }
}
handles
{
    centre { box (0.4 0.4 0.4) (0.6 0.6 0.6); displacement (0.02 0 0); }
}
)D");
    // Target: the plane z = 1.1 (two large triangles).
    write_text(dir / "constant/triSurface/lid.stl",
               "solid lid\n"
               " facet normal 0 0 1\n  outer loop\n   vertex -5 -5 1.1\n   vertex 5 -5 1.1\n"
               "   vertex 5 5 1.1\n  endloop\n endfacet\n"
               " facet normal 0 0 1\n  outer loop\n   vertex -5 -5 1.1\n   vertex 5 5 1.1\n"
               "   vertex -5 5 1.1\n  endloop\n endfacet\nendsolid lid\n");
    // yMin moves by -0.03 in y (its boundaryField value), everything else is zero.
    write_text(
        dir / "0/pointDisplacement",
        R"D(FoamFile { version 2.0; format ascii; class pointVectorField; object pointDisplacement; }
dimensions [0 1 0 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{
    yMin { type fixedValue; value uniform (0 -0.03 0); }
    ".*" { type fixedValue; value uniform (0 0 0); }
}
)D");
    const RunResult r = run({"-case", dir.string(), "-json", (dir / "m.json").string()});
    ASSERT_EQ(r.code, 0) << r.err << r.log;
    ASSERT_EQ(times(dir), (std::vector<std::string>{"0", "1"})) << "first time after 0";
    const Points moved = io::read_points_file(dir / "1/polyMesh/points");
    const auto at = [&](int i, int j, int k) { return i + 5 * (j + 5 * k); };
    // Interior of the lid: onto the plane z = 1.1.
    EXPECT_NEAR(moved(at(2, 2, 4), 2), 1.1, 1e-10);
    EXPECT_NEAR(moved(at(2, 2, 4), 0), 0.5, 1e-10);
    // Interior of yMin: the field's value.
    EXPECT_NEAR(moved(at(2, 0, 2), 1), -0.03, 1e-10);
    // The handle point at the centre.
    EXPECT_NEAR(moved(at(2, 2, 2), 0), 0.52, 1e-10);
    // An interior point of xMin stays.
    EXPECT_LE((moved.row(at(0, 2, 2)) - mesh.points.row(at(0, 2, 2))).norm(), 1e-10);
    const nlohmann::json j = nlohmann::json::parse(read_text(dir / "m.json"));
    EXPECT_EQ(j["handlePoints"].get<int>(), 1);
    EXPECT_GT(j["conflicts"].get<int>(), 0) << "lid and yMin edges meet the fixed sides";
}

TEST(MorphMesh, two_d_case_stays_two_d_through_the_files)
{
    const PolyMesh mesh = test::make_block_mesh(
        6, 6, 1, [](double u, double v, double w) { return Vector3(u, v, 0.1 * w); },
        {"patch", "patch", "patch", "patch", "empty", "empty"});
    const fs::path dir = make_case("two_d", mesh, R"D(
conflicts last;
boundary { yMax { type rotate; origin (0.5 1 0); axis (0 0 1); angle 5; } }
)D");
    const RunResult r = run({"-case", dir.string()});
    ASSERT_EQ(r.code, 0) << r.err << r.log;
    const Points moved = io::read_points_file(dir / "1/polyMesh/points");
    const Index layer = 7 * 7;
    for (Index p = 0; p < layer; ++p)
    {
        EXPECT_EQ(moved(p, 2), mesh.points(p, 2));
        EXPECT_EQ(moved(p + layer, 2), mesh.points(p + layer, 2));
        EXPECT_EQ(moved(p, 0), moved(p + layer, 0));
        EXPECT_EQ(moved(p, 1), moved(p + layer, 1));
    }
    EXPECT_NE(r.log.find("2D case"), std::string::npos);
}

//! Runs OpenFOAM's checkMesh at the latest time; returns the number of failed checks
//! (0 for "Mesh OK."), -1 if the output has neither.
int openfoam_failed_checks(const fs::path& dir, std::string& output)
{
    const std::string cmd = "checkMesh -case '" + dir.string() + "' -latestTime 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (pipe == nullptr)
        return -1;
    std::array<char, 4096> buf{};
    output.clear();
    while (fgets(buf.data(), buf.size(), pipe) != nullptr)
        output += buf.data();
    pclose(pipe);
    if (output.find("\nMesh OK.") != std::string::npos)
        return 0;
    std::smatch m;
    if (std::regex_search(output, m, std::regex(R"(Failed (\d+) mesh checks)")))
        return std::stoi(m[1]);
    return -1;
}

TEST(MorphMesh, two_d_case_onto_a_surface_fits_each_point_pair_once)
{
    // A surface target projects the front and back point of a pair separately. Their
    // prescriptions may differ (a target tilted out of the 2D plane): the pair must reach
    // the fit as one handle (two handles at one position with different values are an RBF
    // error), and the case stays 2D.
    const PolyMesh mesh = test::make_block_mesh(
        6, 6, 1, [](double u, double v, double w) { return Vector3(u, v, 0.1 * w); },
        {"patch", "patch", "patch", "patch", "empty", "empty"});
    for (const double tilt : {0.0, 0.2}) // the plane y = 1.05 + 0.1 x + tilt z
    {
        const fs::path dir = make_case("two_d_surface_" + std::to_string(int(tilt * 10)), mesh,
                                       R"D(
conflicts last;
boundary { yMax { type surface; file "constant/triSurface/slope.stl"; } }
)D");
        std::ostringstream stl;
        const auto y = [&](double x, double z) { return 1.05 + 0.1 * x + tilt * z; };
        stl << "solid slope\n";
        for (const auto& tri : {std::array<double, 6>{-1, -1, 2, -1, 2, 1},
                                std::array<double, 6>{-1, -1, 2, 1, -1, 1}})
        {
            stl << " facet normal 0 0 0\n  outer loop\n";
            for (int k = 0; k < 3; ++k)
                stl << "   vertex " << tri[2 * k] << ' ' << y(tri[2 * k], tri[2 * k + 1]) << ' '
                    << tri[2 * k + 1] << "\n";
            stl << "  endloop\n endfacet\n";
        }
        stl << "endsolid slope\n";
        write_text(dir / "constant/triSurface/slope.stl", stl.str());
        const RunResult r = run({"-case", dir.string(), "-json", (dir / "m.json").string()});
        ASSERT_EQ(r.code, 0) << "tilt " << tilt << ": " << r.err << r.log;
        const Points moved = io::read_points_file(dir / "1/polyMesh/points");
        const Index layer = 7 * 7;
        for (Index p = 0; p < layer; ++p)
        {
            EXPECT_EQ(moved(p, 2), mesh.points(p, 2));
            EXPECT_EQ(moved(p, 0), moved(p + layer, 0)) << "point " << p;
            EXPECT_EQ(moved(p, 1), moved(p + layer, 1)) << "point " << p;
        }
        if (tilt == 0.0) // both planes agree: exact
        {
            const nlohmann::json j = nlohmann::json::parse(read_text(dir / "m.json"));
            EXPECT_LE(j["relativeConstraintError"].get<double>(), 1e-9);
        }
    }
}

TEST(MorphMesh, openfoam_checkmesh_reads_the_squeezed_pipe_ascii_and_binary)
{
    if (!test::openfoam_available())
        GTEST_SKIP() << "OpenFOAM not installed: checkMesh on the morphed pipe is skipped";
    const io::FoamPolyMesh shipped = test::read_shipped_pipe();
    // Radial squeeze of the whole wall by 0.3 R about the axis; inlet/outlet slide.
    const std::string dict = R"D(
boundary
{
    wall   { type scale; origin (0 0 0); factor (0.7 0.7 1); }
    "(inlet|outlet)" { type slip; }
}
)D";
    for (const io::FoamFormat format : {io::FoamFormat::ascii, io::FoamFormat::binary})
    {
        const std::string name = format == io::FoamFormat::ascii ? "pipe_ascii" : "pipe_binary";
        const fs::path dir = make_case(name, shipped.mesh, dict, format);
        std::string before_text;
        const int before = openfoam_failed_checks(dir, before_text);
        ASSERT_GE(before, 0) << before_text;
        const RunResult r = run({"-case", dir.string()});
        ASSERT_EQ(r.code, 0) << r.err << r.log;
        std::string after_text;
        const int after = openfoam_failed_checks(dir, after_text);
        ASSERT_NE(after_text.find("Time = 1"), std::string::npos)
            << "checkMesh must read the morphed time: " << after_text;
        EXPECT_LE(after, before) << after_text;
        // checkMesh sees the squeeze: scaling radially by 0.7 is affine, which the RBF's
        // linear term reproduces exactly, so the volume shrinks by 0.49 (to round-off).
        const std::regex volume(R"(Total volume = ([0-9.eE+-]+[0-9])\.\s)");
        std::smatch mb, ma;
        ASSERT_TRUE(std::regex_search(before_text, mb, volume)) << before_text;
        ASSERT_TRUE(std::regex_search(after_text, ma, volume)) << after_text;
        // checkMesh prints 15 significant digits (writePrecision 15).
        EXPECT_NEAR(std::stod(ma[1]) / std::stod(mb[1]), 0.49, 1e-9);
    }
}

} // namespace
} // namespace meshmorph::app
