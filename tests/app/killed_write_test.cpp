// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 12, "no mesh ever lost": morphMesh killed with SIGKILL at random moments while it
// writes (many trials, with and without -overwrite) leaves at the destination the old
// points file or the complete new one, byte for byte, never a partial one; and what a
// killed run leaves behind (temporaries, an empty time directory) does not trip a later
// run, which succeeds and removes the stale temporaries.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <regex>
#include <thread>

#include "fault_case.h"
#include "meshmorph/app/exit_status.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"

namespace fs = std::filesystem;
using namespace meshmorph;

namespace
{

// 30^3 cells: an ascii points file of about 1.7 MB, written (and fsync'ed) in some tens of
// milliseconds, the window the kills aim at; a whole run takes about half a second.
constexpr int cells_per_axis = 30;
// MESHMORPH_KILL_TRIALS=N runs N trials per mode instead (longer campaigns by hand).
const int trials_per_mode =
    std::getenv("MESHMORPH_KILL_TRIALS") ? std::atoi(std::getenv("MESHMORPH_KILL_TRIALS")) : 25;
// Printed just before the write stage (after the checks); the kills are timed from here.
const char* const before_write = "Mesh quality before and after the morph:";

fs::path make_large_case(const std::string& name)
{
    const fs::path dir = test::scratch_dir("faults/" + name);
    io::write_poly_mesh(test::make_box_mesh(cells_per_axis, cells_per_axis, cells_per_axis),
                        io::default_poly_mesh_files(io::FoamFormat::ascii), dir, "constant");
    fs::create_directories(dir / "0"); // -time 0: every run writes 1/, whatever 1/ holds
    test::write_file(dir / "system/controlDict",
                     "FoamFile { version 2.0; format ascii; class dictionary; object "
                     "controlDict; }\ndeltaT 1;\n");
    // FFD needs no fit: the run is reading, checking and writing.
    test::write_morph_dict(dir, "method ffd;\nffd { lattice (4 4 4); displacements "
                                "( ((1 1 1) (0.01 0.02 0.03)) ((2 2 2) (0 0 -0.02)) ); }\n");
    return dir;
}

std::vector<std::string> morph_argv(const fs::path& dir, bool overwrite)
{
    std::vector<std::string> argv{MESHMORPH_MORPH_MESH_EXE, "-case", dir.string(), "-time", "0"};
    if (overwrite)
        argv.push_back("-overwrite");
    return argv;
}

//! Hidden temporaries of atomic writes in `dir` (".points.<host>.<pid>.<n>.tmp").
std::vector<std::string> temporaries(const fs::path& dir)
{
    std::vector<std::string> found;
    if (fs::is_directory(dir))
        for (const fs::directory_entry& e : fs::directory_iterator(dir))
        {
            const std::string name = e.path().filename().string();
            if (name.size() > 4 && name[0] == '.' && name.substr(name.size() - 4) == ".tmp")
                found.push_back(name);
        }
    return found;
}

struct Reference
{
    std::string bytes;    //!< the complete new points file
    double write_seconds; //!< how long the write stage took
};

Reference reference_run(const fs::path& dir, bool overwrite, const fs::path& destination)
{
    test::ProcessRun r = test::run_process(morph_argv(dir, overwrite));
    EXPECT_EQ(r.status, app::exit_ok) << r.err;
    std::smatch m;
    const bool timed = std::regex_search(r.out, m, std::regex(R"(, write ([0-9.e+-]+)\n)"));
    EXPECT_TRUE(timed) << r.out;
    return {test::read_file(destination), timed ? std::stod(m[1]) : 0.1};
}

struct Tally
{
    int old_or_absent = 0, complete_new = 0, temporaries_left = 0;
};

//! One kill at a random moment of the write stage (uniform over 1.5 times its duration
//! after the marker line); checks the destination; returns what it found.
void kill_once(const fs::path& dir, bool overwrite, const fs::path& destination,
               const std::string& old_bytes, const Reference& ref, std::mt19937& rng, Tally& tally)
{
    std::uniform_real_distribution<double> delay(0.0, 1.5 * ref.write_seconds + 0.002);
    test::SpawnedProcess p(morph_argv(dir, overwrite));
    ASSERT_TRUE(p.wait_for_output(before_write)) << p.output();
    std::this_thread::sleep_for(std::chrono::duration<double>(delay(rng)));
    p.kill(SIGKILL);
    const int status = p.wait();
    EXPECT_TRUE(status == -SIGKILL || status == app::exit_ok) << status;

    if (!fs::exists(destination))
    {
        EXPECT_TRUE(old_bytes.empty()) << "the old points file disappeared";
    }
    const std::string now = fs::exists(destination) ? test::read_file(destination) : "";
    const bool is_old = now == old_bytes;
    const bool is_new = now == ref.bytes;
    ASSERT_TRUE(is_old || is_new) << "partial points file: " << now.size() << " bytes (old "
                                  << old_bytes.size() << ", new " << ref.bytes.size() << ")";
    if (is_new)
    {
        EXPECT_EQ(io::read_points_file(destination).rows(),
                  (cells_per_axis + 1) * (cells_per_axis + 1) * (cells_per_axis + 1));
    }
    ++(is_new ? tally.complete_new : tally.old_or_absent);
    tally.temporaries_left += int(temporaries(destination.parent_path()).size() +
                                  (overwrite ? 0 : temporaries(dir).size()));
}

void report(const char* mode, const Tally& t)
{
    std::cout << "[ KILLED   ] " << mode << ": " << trials_per_mode << " trials, "
              << t.old_or_absent << " left the old (or no) points file, " << t.complete_new
              << " the complete new one, " << t.temporaries_left
              << " temporaries left behind, none partial\n";
}

} // namespace

TEST(KilledWrite, next_time_points_are_old_or_new_and_a_later_run_cleans_up)
{
    const fs::path ref_dir = make_large_case("killed_reference_next");
    const Reference ref = reference_run(ref_dir, false, ref_dir / "1/polyMesh/points");
    const fs::path dir = make_large_case("killed_next");
    const fs::path destination = dir / "1/polyMesh/points";
    // Half the trials write over an earlier result (any valid points file: the input's),
    // half into a fresh time directory.
    const std::string earlier = test::read_file(dir / "constant/polyMesh/points");
    std::mt19937 rng(20261123);
    Tally tally;
    for (int trial = 0; trial < trials_per_mode; ++trial)
    {
        const bool over_earlier = trial % 2 == 0;
        if (over_earlier)
            test::write_file(destination, earlier);
        else
            fs::remove(destination);
        kill_once(dir, false, destination, over_earlier ? earlier : "", ref, rng, tally);
        if (HasFatalFailure())
            return;
    }
    report("next time", tally);

    // A later run succeeds, writes the complete file and leaves no temporaries.
    const test::ProcessRun later = test::run_process(morph_argv(dir, false));
    EXPECT_EQ(later.status, app::exit_ok) << later.err;
    EXPECT_TRUE(test::read_file(destination) == ref.bytes) << "not the complete new file";
    EXPECT_EQ(temporaries(destination.parent_path()), std::vector<std::string>{});
    EXPECT_EQ(temporaries(dir), std::vector<std::string>{});
}

TEST(KilledWrite, overwritten_points_are_old_or_new_and_the_original_is_kept)
{
    const fs::path ref_dir = make_large_case("killed_reference_overwrite");
    const fs::path ref_points = ref_dir / "constant/polyMesh/points";
    const std::string original = test::read_file(ref_points);
    const Reference ref = reference_run(ref_dir, true, ref_points);
    const fs::path dir = make_large_case("killed_overwrite");
    const fs::path destination = dir / "constant/polyMesh/points";
    const fs::path orig = dir / "constant/polyMesh/points.orig";
    std::mt19937 rng(20261124);
    Tally tally;
    for (int trial = 0; trial < trials_per_mode; ++trial)
    {
        test::write_file(destination, original); // each trial starts from the unmorphed case
        fs::remove(orig);
        kill_once(dir, true, destination, original, ref, rng, tally);
        if (HasFatalFailure())
            return;
        // The original is kept, complete, before the points are replaced.
        if (test::read_file(destination) == ref.bytes)
        {
            EXPECT_TRUE(fs::exists(orig)) << "points replaced before points.orig was kept";
        }
        if (fs::exists(orig))
        {
            EXPECT_TRUE(test::read_file(orig) == original) << "partial points.orig";
        }
    }
    report("-overwrite", tally);

    // A run killed between keeping the original and replacing the points left an orig equal
    // to the points: a later run must not call that "morphed before".
    test::write_file(destination, original);
    test::write_file(orig, original);
    const test::ProcessRun later = test::run_process(morph_argv(dir, true));
    EXPECT_EQ(later.status, app::exit_ok) << later.err;
    EXPECT_EQ(later.err.find("was morphed before"), std::string::npos) << later.err;
    EXPECT_TRUE(test::read_file(destination) == ref.bytes) << "not the complete new file";
    EXPECT_TRUE(test::read_file(orig) == original) << "points.orig is not the original";
    EXPECT_EQ(temporaries(destination.parent_path()), std::vector<std::string>{});
}

TEST(KilledWrite, an_interrupted_run_leaves_no_report_saying_written)
{
    // timeout -s INT 4 morphMesh -overwrite -json r.json used to leave an earlier r.json
    // saying `written: true`. Interrupted (SIGINT, SIGTERM) or killed (SIGKILL) at the check,
    // the report says the run did not finish, and no temporary is left in the case.
    const fs::path dir = make_large_case("killed_report");
    const fs::path json = dir / "r.json";
    std::vector<std::string> argv = morph_argv(dir, true);
    argv.insert(argv.end(), {"-json", json.string()});
    for (const int sig : {SIGINT, SIGTERM, SIGKILL})
    {
        test::write_file(json, "{\"written\": true, \"exitStatus\": 0}\n");
        test::SpawnedProcess p(argv);
        ASSERT_TRUE(p.wait_for_output("Read mesh")) << p.output();
        p.kill(sig);
        const int status = p.wait();
        ASSERT_EQ(status, -sig) << "the run ended before the signal: " << p.output();
        const std::string report = test::read_file(json);
        EXPECT_NE(report.find("\"written\": false"), std::string::npos) << report;
        EXPECT_NE(report.find("did not finish"), std::string::npos) << report;
        EXPECT_EQ(temporaries(dir / "constant/polyMesh"), std::vector<std::string>{});
        EXPECT_EQ(temporaries(dir), std::vector<std::string>{});
    }
}
