// SPDX-License-Identifier: GPL-3.0-or-later
// The conventions morphMesh and checkMeshQuality share, run in-process on generated cases:
// `-vtk` (a flag writing into the case's VTK/ folder) and `-vtkFile FILE`, the error for the
// old `checkMeshQuality -vtk FILE`, the "Error: " prefix, and the log going to the streams
// the application is given (info with the report on out, warnings and errors on err).
#include <gtest/gtest.h>

#include "check_mesh_run.h"

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "helpers.h"
#include "meshmorph/app/check_mesh_case.h"
#include "meshmorph/app/exit_status.h"
#include "meshmorph/core/config.h"
#include "meshmorph/io/write_poly_mesh.h"
#include "morph_run.h"

namespace fs = std::filesystem;
using namespace meshmorph;

namespace
{

fs::path write_case(const std::string& name, const PolyMesh& mesh)
{
    const fs::path dir = test::scratch_dir("app_conventions/" + name);
    io::write_poly_mesh(mesh, io::default_poly_mesh_files(io::FoamFormat::ascii), dir, "constant");
    test::write_text(dir / "system/controlDict",
                     "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; "
                     "}\napplication morphMesh; startFrom latestTime; startTime 0; "
                     "stopAt endTime;\nendTime 1; deltaT 1; writeControl timeStep; "
                     "writeInterval 1;\nwritePrecision 10;\n");
    test::write_text(dir / "system/morphDict",
                     "FoamFile { version 2.0; format ascii; class dictionary; object morphDict; "
                     "}\nmethod rbf;\nconflicts last;\n"
                     "boundary { zMax { type translate; vector (0 0 0.05); } }\n");
    return dir;
}

std::string read_text(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

// -vtk is a flag in both applications: it writes into the case's VTK/ folder, as foamToVTK.
TEST(AppConventions, vtk_flag_writes_into_the_case_vtk_folder_in_both_applications)
{
#if MESHMORPH_WITH_VTK
    const fs::path dir = write_case("vtk_flag", test::make_box_mesh(3, 3, 3));
    const test::AppRun c = test::run_check_mesh_quality({"-case", dir.string(), "-vtk"});
    ASSERT_EQ(c.status, app::exit_ok) << c.err;
    const fs::path checked = dir / "VTK" / "checkMeshQuality_constant.vtu";
    EXPECT_NE(read_text(checked).find("NumberOfCells=\"27\""), std::string::npos) << checked;
    EXPECT_NE(c.out.find("Wrote " + checked.string()), std::string::npos) << c.out;

    const test::MorphRun m = test::run_morph_mesh({"-case", dir.string(), "-vtk"});
    ASSERT_EQ(m.code, app::exit_ok) << m.err;
    const fs::path morphed = dir / "VTK" / "morphMesh_1.vtu";
    EXPECT_NE(read_text(morphed).find("Name=\"displacement\""), std::string::npos) << morphed;
    EXPECT_NE(m.out.find("Wrote " + morphed.string()), std::string::npos) << m.out;

    // -vtkFile FILE writes FILE instead (relative paths: from the working directory).
    const fs::path own = dir / "elsewhere" / "q.vtu";
    const test::AppRun f = test::run_check_mesh_quality(
        {"-case", dir.string(), "-time", "1", "-vtkFile", own.string()});
    ASSERT_EQ(f.status, app::exit_ok) << f.err;
    EXPECT_NE(read_text(own).find("Name=\"scaledJacobian\""), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "VTK" / "checkMeshQuality_1.vtu"));
#else
    GTEST_SKIP() << "built without VTK: -vtk is rejected";
#endif
}

// Scripts written for the old `checkMeshQuality -vtk FILE` get an error naming the new
// spelling, and nothing is written; the same holds for morphMesh.
TEST(AppConventions, old_vtk_file_spelling_names_vtk_file)
{
    const fs::path dir = write_case("vtk_old", test::make_box_mesh(2, 2, 2));
    const test::AppRun c = test::run_check_mesh_quality({"-case", dir.string(), "-vtk", "q.vtu"});
    EXPECT_EQ(c.status, app::exit_input_error);
    EXPECT_EQ(c.err.rfind("Error: unexpected argument 'q.vtu' after -vtk, which takes no "
                          "argument: -vtk writes VTK/checkMeshQuality_[<region>_]<time>.vtu in "
                          "the case; to choose the file, use -vtkFile q.vtu\n",
                          0),
              0u)
        << c.err;
    EXPECT_TRUE(c.out.empty()) << c.out;

    const test::MorphRun m = test::run_morph_mesh({"-case", dir.string(), "-vtk", "m.vtu"});
    EXPECT_EQ(m.code, app::exit_input_error);
    EXPECT_NE(m.err.find("use -vtkFile m.vtu"), std::string::npos) << m.err;
    EXPECT_FALSE(fs::exists(dir / "1"));
}

// The log goes where the application is told: info lines (stage timings) with the report
// on out, in order; warnings on err; -quiet drops the info lines but keeps the report.
TEST(AppConventions, log_lines_go_to_the_application_streams)
{
    const fs::path dir = write_case("log", test::make_box_mesh(2, 2, 2));
    // Both `points` and `points.gz`: reading warns (and reads the plain file).
    fs::copy_file(dir / "constant/polyMesh/points", dir / "constant/polyMesh/points.gz");
    const test::AppRun c = test::run_check_mesh_quality({"-case", dir.string()});
    ASSERT_EQ(c.status, app::exit_ok) << c.err;
    const std::size_t read = c.out.find("Read mesh (8 cells) in ");
    const std::size_t time = c.out.find("Time = constant");
    const std::size_t checked = c.out.find("Checked mesh in ");
    ASSERT_NE(read, std::string::npos) << c.out;
    ASSERT_NE(checked, std::string::npos) << c.out;
    EXPECT_LT(read, time);
    EXPECT_LT(time, checked);
    EXPECT_EQ(c.err.rfind("Warning: Both ", 0), 0u) << c.err;
    EXPECT_NE(c.err.find("points.gz"), std::string::npos) << c.err;
    EXPECT_EQ(c.out.find("Warning"), std::string::npos);

    const test::AppRun quiet = test::run_check_mesh_quality({"-case", dir.string(), "-quiet"});
    ASSERT_EQ(quiet.status, app::exit_ok) << quiet.err;
    EXPECT_EQ(quiet.out.rfind("Time = constant\n", 0), 0u) << quiet.out;
    EXPECT_EQ(quiet.out.find("Read mesh"), std::string::npos) << quiet.out;
    EXPECT_EQ(quiet.out.find("Checked mesh"), std::string::npos) << quiet.out;
    EXPECT_EQ(quiet.err, c.err);

    // morphMesh: the library's info lines come after the banner and before the timings.
    const test::MorphRun m = test::run_morph_mesh({"-case", dir.string()});
    ASSERT_EQ(m.code, app::exit_ok) << m.err;
    const std::size_t banner = m.out.find("Exec   : morphMesh");
    const std::size_t step = m.out.find("Step 1: motion 0 -> 1");
    const std::size_t timings = m.out.find("Timings [s]: ");
    ASSERT_NE(step, std::string::npos) << m.out;
    EXPECT_LT(banner, step);
    EXPECT_LT(step, timings);
    EXPECT_EQ(m.err.rfind("Warning: Both ", 0), 0u) << m.err;
}

// One error prefix: usage errors, input errors and refusals all read "Error: ...".
TEST(AppConventions, errors_have_one_prefix_in_both_applications)
{
    const fs::path dir = write_case("errors", test::make_box_mesh(2, 2, 2));
    for (const test::AppRun& r : {test::run_check_mesh_quality({"-bogus"}),
                                  test::run_check_mesh_quality({"-case", (dir / "none").string()})})
    {
        EXPECT_EQ(r.status, app::exit_input_error);
        EXPECT_EQ(r.err.rfind("Error: ", 0), 0u) << r.err;
    }
    test::write_text(dir / "system/morphDict", "FoamFile { version 2.0; format ascii; class "
                                               "dictionary; object morphDict; }\nmethod nope;\n");
    for (const test::MorphRun& r :
         {test::run_morph_mesh({"-bogus"}), test::run_morph_mesh({"-case", dir.string()})})
    {
        EXPECT_EQ(r.code, app::exit_input_error);
        EXPECT_EQ(r.err.rfind("Error: ", 0), 0u) << r.err;
        EXPECT_EQ(r.err.find("Internal"), std::string::npos) << r.err;
    }
}
