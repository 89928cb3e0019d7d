// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of io/case_instance.h: time directories, -time/-latestTime, instance lookup.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "io_test_util.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/case_instance.h"

using namespace meshmorph;
using namespace meshmorph::io;
namespace fs = std::filesystem;

namespace
{

std::vector<std::string> names(const std::vector<TimeDir>& times)
{
    std::vector<std::string> out;
    for (const TimeDir& t : times)
        out.push_back(t.name);
    return out;
}

void touch(const fs::path& path)
{
    test::write_bytes(path, "x");
}

} // namespace

TEST(CaseInstance, lists_numeric_directories_sorted_by_value)
{
    const fs::path dir = test::scratch_dir("ci_times");
    for (const char* d : {"0", "0.5", "1e-05", "10", "constant", "system", "0.orig", "2.5e+01"})
        fs::create_directories(dir / d);
    touch(dir / "3"); // a file, not a directory
    EXPECT_EQ(names(list_times(dir)),
              (std::vector<std::string>{"0", "1e-05", "0.5", "10", "2.5e+01"}));
    EXPECT_TRUE(list_times(dir / "nonexistent").empty());
}

TEST(CaseInstance, selects_first_latest_and_named_times)
{
    const std::vector<TimeDir> times{{"0", 0}, {"0.1", 0.1}, {"0.2", 0.2}};
    EXPECT_EQ(select_time(times, TimeSelection::first_time()), "0");
    EXPECT_EQ(select_time(times, TimeSelection::latest_time()), "0.2");
    EXPECT_EQ(select_time(times, TimeSelection::at("0.1")), "0.1");
    EXPECT_EQ(select_time(times, TimeSelection::at("0.10000000001")), "0.1");
    EXPECT_EQ(select_time(times, TimeSelection::at("1e-1")), "0.1");
    EXPECT_EQ(select_time(times, TimeSelection::at("constant")), "constant");
    EXPECT_EQ(select_time({}, TimeSelection::latest_time()), "constant");
    EXPECT_EQ(select_time({}, TimeSelection::first_time()), "constant");
    EXPECT_THROW(select_time(times, TimeSelection::at("0.15")), InvalidInput);
    EXPECT_THROW(select_time(times, TimeSelection::at("abc")), InvalidInput);
}

TEST(CaseInstance, points_and_topology_instances_are_found_separately)
{
    const fs::path dir = test::scratch_dir("ci_instances");
    for (const char* f : {"points", "faces", "owner", "neighbour", "boundary"})
        touch(dir / "constant/polyMesh" / f);
    touch(dir / "1/polyMesh/points.gz"); // moved points only
    touch(dir / "2/polyMesh/points");    // new topology
    touch(dir / "2/polyMesh/faces");
    fs::create_directories(dir / "3"); // fields only
    const std::vector<TimeDir> times = list_times(dir);
    EXPECT_EQ(find_instance(dir, times, "constant", "points"), "constant");
    EXPECT_EQ(find_instance(dir, times, "1", "points"), "1");
    EXPECT_EQ(find_instance(dir, times, "1", "faces"), "constant");
    EXPECT_EQ(find_instance(dir, times, "1.5", "points"), "1");
    EXPECT_EQ(find_instance(dir, times, "2", "faces"), "2");
    EXPECT_EQ(find_instance(dir, times, "3", "points"), "2");
    EXPECT_EQ(find_instance(dir, times, "0.5", "points"), "constant");
    EXPECT_THROW(find_instance(dir, times, "1", "cellZones"), IoError);
    EXPECT_EQ(poly_mesh_dir(dir, "1", "solid"), dir / "1/solid/polyMesh");
    EXPECT_EQ(poly_mesh_dir(dir, "1", "region0"), dir / "1/polyMesh");
}

TEST(CaseInstance, the_start_time_skips_motion_results)
{
    // A motion result is moved points without a mesh (morphMesh, moveMesh, reconstructPar
    // of those); whole meshes (snappyHexMesh without -overwrite) and fields are not.
    const fs::path dir = test::scratch_dir("ci_start");
    for (const char* f : {"points", "faces", "owner", "neighbour", "boundary"})
        touch(dir / "constant/polyMesh" / f);
    touch(dir / "1/polyMesh/points.gz");
    touch(dir / "2/polyMesh/points");
    touch(dir / "2/polyMesh/faces");
    fs::create_directories(dir / "3");
    touch(dir / "4/fluid/polyMesh/points");
    const std::vector<TimeDir> times = list_times(dir);
    EXPECT_TRUE(is_motion_result(dir, "1"));
    EXPECT_FALSE(is_motion_result(dir, "2"));
    EXPECT_FALSE(is_motion_result(dir, "3"));
    EXPECT_FALSE(is_motion_result(dir, "4"));
    EXPECT_TRUE(is_motion_result(dir, "4", "fluid"));
    EXPECT_EQ(names(start_times(dir, times)), (std::vector<std::string>{"2", "3", "4"}));
    EXPECT_EQ(names(start_times(dir, times, "fluid")), (std::vector<std::string>{"1", "2", "3"}));
    EXPECT_EQ(select_time(start_times(dir, times), TimeSelection::start_time()), "2");
    // Only results: the case starts from constant, and its next time is the first one's.
    const fs::path results = test::scratch_dir("ci_start_results");
    touch(results / "constant/polyMesh/points");
    touch(results / "constant/polyMesh/faces");
    touch(results / "1/polyMesh/points");
    touch(results / "2/polyMesh/points");
    const std::vector<TimeDir> starts = start_times(results, list_times(results));
    EXPECT_TRUE(starts.empty());
    EXPECT_EQ(select_time(starts, TimeSelection::start_time()), "constant");
    EXPECT_EQ(next_time_name(starts, "constant", TimeSettings{}), "1");
}

TEST(CaseInstance, formats_time_names_like_openfoam)
{
    EXPECT_EQ(format_time_name(1), "1");
    EXPECT_EQ(format_time_name(0.005), "0.005");
    EXPECT_EQ(format_time_name(1e-05), "1e-05");
    EXPECT_EQ(format_time_name(0.1 + 0.2), "0.3");
    EXPECT_EQ(format_time_name(-0.0), "0");
    EXPECT_EQ(format_time_name(2, TimeFormat::fixed, 3), "2.000");
    EXPECT_EQ(format_time_name(2, TimeFormat::scientific, 2), "2.00e+00");
}

TEST(CaseInstance, next_time_uses_delta_t_and_raises_precision_when_needed)
{
    TimeSettings s;
    EXPECT_EQ(next_time_name({{"0", 0}}, "0", s), "1");
    EXPECT_EQ(next_time_name({}, "constant", s), "1");
    s.delta_t = 0.1;
    EXPECT_EQ(next_time_name({{"0", 0}, {"0.2", 0.2}}, "0.2", s), "0.3");
    s.delta_t = 1e-7;
    s.precision = 3;
    // 1 + 1e-7 prints as "1" at 3 digits: more digits are used.
    EXPECT_EQ(next_time_name({{"1", 1}}, "1", s), "1.0000001");
}

TEST(CaseInstance, reads_time_settings_from_control_dict)
{
    const fs::path dir = test::scratch_dir("ci_control");
    EXPECT_EQ(read_time_settings(dir).delta_t, 1.0); // no controlDict: defaults
    test::write_bytes(
        dir / "system/controlDict",
        "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
        "deltaT 0.005;\ntimeFormat fixed;\ntimePrecision 4;\n");
    const TimeSettings s = read_time_settings(dir);
    EXPECT_EQ(s.delta_t, 0.005);
    EXPECT_EQ(s.format, TimeFormat::fixed);
    EXPECT_EQ(s.precision, 4);
    test::write_bytes(
        dir / "system/controlDict",
        "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
        "deltaT -1;\n");
    const std::string msg = test::error_of([&] { read_time_settings(dir); });
    EXPECT_NE(msg.find("controlDict:2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("-overwrite writes in place"), std::string::npos)
        << "the way out for a mesh-generation case's deltaT 0: " << msg;
}

TEST(CaseInstance, a_stock_control_dict_with_function_objects_and_computed_entries_reads)
{
    // What OpenFOAM's tutorials ship (pitzDaily: #includeFunc; others: #calc, #codeStream,
    // #includeEtc): the time settings read, the rest is skipped.
    const fs::path dir = test::scratch_dir("ci_control_stock");
    test::write_bytes(
        dir / "system/controlDict",
        "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
        "application simpleFoam;\nendTime #calc \"2*1000\";\ndeltaT 0.5;\n"
        "writeInterval #codeStream { code #{ os << 100; #}; };\n"
        "functions\n{\n    #includeFunc streamlines\n    #includeFunc mag(U)\n"
        "    #includeFunc singleGraph(start=(0 0 0), end=(1 0 0),\n        fields=(U p))\n"
        "    #includeEtc \"caseDicts/postProcessing/forces/forces.cfg\"\n}\n"
        "timePrecision 5;\n");
    const TimeSettings s = read_time_settings(dir);
    EXPECT_EQ(s.delta_t, 0.5);
    EXPECT_EQ(s.precision, 5) << "entries after the directives are still read";
}

TEST(CaseInstance, every_shipped_tutorial_control_dict_gives_its_time_settings_without_a_warning)
{
    // morphMesh reads controlDict in every case it morphs; what the function objects need
    // (an #includeEtc skipped here defines windAroundBuildings' ${..colourScheme.paraview})
    // is no concern of its time settings, and a warning about it would be noise.
    const fs::path examples = "/usr/share/doc/openfoam-examples/examples";
    std::vector<fs::path> cases;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(examples, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename() == "controlDict" &&
            it->path().parent_path().filename() == "system")
            cases.push_back(it->path().parent_path().parent_path());
    if (cases.empty())
        GTEST_SKIP() << "openfoam-examples not installed: no tutorial controlDicts to read";
    std::sort(cases.begin(), cases.end());
    std::size_t read = 0;
    for (const fs::path& dir : cases)
    {
        const log::CaptureScope capture;
        try
        {
            const TimeSettings s = read_time_settings(dir);
            EXPECT_GT(s.delta_t, 0.0) << dir;
            ++read;
        }
        catch (const Error& e)
        {
            // Only an entry OpenFOAM alone can compute (#calc, #codeStream), or the deltaT 0
            // of a mesh-generation tutorial (blockMesh/sphere), may stop it, named.
            const std::string what = e.what();
            EXPECT_TRUE(what.find('#') != std::string::npos ||
                        what.find("deltaT must be positive") != std::string::npos)
                << dir << ": " << what;
        }
        EXPECT_EQ(capture.text().find("Warning"), std::string::npos) << dir << "\n"
                                                                     << capture.text();
    }
    EXPECT_GT(read, cases.size() / 2) << "most tutorials' time settings read";
}

TEST(CaseInstance, a_needed_entry_that_only_openfoam_can_compute_is_an_error_naming_it)
{
    const fs::path dir = test::scratch_dir("ci_control_calc");
    test::write_bytes(
        dir / "system/controlDict",
        "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
        "deltaT #calc \"1.0/200\";\n");
    const std::string msg = test::error_of([&] { read_time_settings(dir); });
    EXPECT_NE(msg.find("controlDict:2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("deltaT"), std::string::npos) << msg;
    EXPECT_NE(msg.find("#calc"), std::string::npos) << msg;
}
