// SPDX-License-Identifier: GPL-3.0-or-later
// OpenFOAM-oracle tests of the polyMesh reader/writer: OpenFOAM generates a curved-edge
// blockMesh case in ASCII, binary and compressed forms; meshmorph reads each and writes it
// back; OpenFOAM's checkMesh must then report exactly the same statistics for meshmorph's
// files as for its own. Skipped when OpenFOAM is not installed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "io_test_util.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"

using namespace meshmorph;
using namespace meshmorph::io;
namespace fs = std::filesystem;

namespace
{

const fs::path scripts = fs::path(MESHMORPH_SOURCE_DIR) / "scripts/openfoam";

// The statistics part of a checkMesh log: from "Mesh stats" to "End", without the lines
// that name the case or time.
std::vector<std::string> check_mesh_stats(const fs::path& case_dir, const std::string& args,
                                          const std::string& log)
{
    const int rc = test::run_in(case_dir, "checkMesh " + args, log);
    EXPECT_EQ(rc, 0) << "checkMesh failed in " << case_dir << ", see " << log;
    std::ifstream in(case_dir / log);
    std::vector<std::string> lines;
    bool inside = false;
    for (std::string line; std::getline(in, line);)
    {
        if (line.find("Mesh stats") != std::string::npos)
            inside = true;
        if (!inside)
            continue;
        lines.push_back(line);
        if (line == "End")
            break;
    }
    EXPECT_GT(lines.size(), 20u) << "no statistics in " << (case_dir / log);
    return lines;
}

// A new case with `from`'s system/ and no mesh.
fs::path empty_case_like(const fs::path& from, const fs::path& to)
{
    fs::remove_all(to);
    fs::create_directories(to / "constant");
    fs::copy(from / "system", to / "system", fs::copy_options::recursive);
    return to;
}

} // namespace

TEST(PolyMeshOpenFoam, checkmesh_reports_the_same_for_meshmorph_output)
{
    if (!test::openfoam_available())
        GTEST_SKIP() << "OpenFOAM not installed: checkMesh comparison of written meshes skipped";
    const fs::path work = test::scratch_dir("pm_openfoam");
    ASSERT_EQ(test::run_in(work, "'" + (scripts / "curved-block.sh").string() + "' ascii",
                           "log.curved-block"),
              0)
        << "see " << work / "log.curved-block";
    ASSERT_EQ(test::run_in(work,
                           "'" + (scripts / "convert-format.sh").string() + "' ascii binary binary",
                           "log.binary"),
              0);
    ASSERT_EQ(
        test::run_in(work,
                     "'" + (scripts / "convert-format.sh").string() + "' ascii gz ascii compressed",
                     "log.gz"),
        0);
    ASSERT_EQ(test::run_in(work,
                           "'" + (scripts / "convert-format.sh").string() +
                               "' ascii binary_gz binary compressed",
                           "log.binary_gz"),
              0);

    const FoamPolyMesh reference = read_poly_mesh(work / "ascii");
    for (const char* variant : {"ascii", "binary", "gz", "binary_gz"})
    {
        SCOPED_TRACE(variant);
        const fs::path theirs = work / variant;
        const FoamPolyMesh m = read_poly_mesh(theirs);
        EXPECT_EQ(m.mesh.faces, reference.mesh.faces);
        EXPECT_EQ(m.mesh.points, reference.mesh.points);
        EXPECT_EQ(m.points.header.is_binary(), std::string(variant).find("binary") == 0);
        EXPECT_EQ(m.points.is_compressed, std::string(variant).find("gz") != std::string::npos);

        const std::vector<std::string> expected =
            check_mesh_stats(theirs, "-constant", "log.checkMesh.theirs");

        // The whole mesh rewritten by meshmorph, in the same form.
        const fs::path ours = empty_case_like(theirs, work / (std::string("ours_") + variant));
        write_poly_mesh(m.mesh, m, ours, "constant");
        EXPECT_EQ(check_mesh_stats(ours, "-constant", "log.checkMesh.ours"), expected);

        // Only the points, into a new time directory (topology stays in constant).
        write_points(m.mesh.points, m.points, theirs, "1");
        EXPECT_EQ(check_mesh_stats(theirs, "-latestTime", "log.checkMesh.time1"), expected);
    }
}

TEST(PolyMeshOpenFoam, openfoam_reads_generated_meshes_in_every_format)
{
    if (!test::openfoam_available())
        GTEST_SKIP() << "OpenFOAM not installed: checkMesh on generated meshes skipped";
    // A mesh meshmorph generates from scratch (no OpenFOAM file read) must be accepted by
    // checkMesh in every format, with the cell count meshmorph computed.
    const PolyMesh mesh = test::make_block_mesh(
        5, 4, 3,
        [](double u, double v, double w)
        { return Vector3(u + 0.1 * v * v, v + 0.05 * std::sin(3 * u), 0.5 * w); },
        {"patch", "patch", "wall", "wall", "patch", "patch"});
    const fs::path work = test::scratch_dir("pm_openfoam_generated");
    ASSERT_EQ(test::run_in(work, "'" + (scripts / "curved-block.sh").string() + "' template",
                           "log.template"),
              0);
    const struct
    {
        const char* name;
        FoamFormat format;
        bool compress;
    } cases[] = {{"ascii", FoamFormat::ascii, false},
                 {"binary", FoamFormat::binary, false},
                 {"ascii_gz", FoamFormat::ascii, true}};
    for (const auto& c : cases)
    {
        SCOPED_TRACE(c.name);
        const fs::path dir = empty_case_like(work / "template", work / c.name);
        write_poly_mesh(mesh, default_poly_mesh_files(c.format, c.compress), dir, "constant");
        const std::vector<std::string> stats = check_mesh_stats(dir, "-constant", "log.checkMesh");
        const std::string cells = "    cells:            " + std::to_string(mesh.n_cells);
        EXPECT_NE(std::find(stats.begin(), stats.end(), cells), stats.end()) << cells;
        EXPECT_NE(std::find(stats.begin(), stats.end(), "Mesh OK."), stats.end());
    }
}
