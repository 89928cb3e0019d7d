// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the option table (meshmorph/app/options.h) and the stage timer format.
#include <gtest/gtest.h>

#include <sstream>

#include "meshmorph/app/banner.h"
#include "meshmorph/app/exit_status.h"
#include "meshmorph/app/options.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/case_instance.h"

using namespace meshmorph;
using namespace meshmorph::app;
using meshmorph::format_seconds;

namespace
{

Options make_options()
{
    return Options("checkMeshQuality", "Checks the mesh.",
                   {{"case", "DIR", "Case directory (default: .)"},
                    {"allGeometry", "", "Include bounding box checks"},
                    {"time", "TIME", "Time to check"}},
                   {{0, "mesh OK"}, {1, "checks failed"}, {2, "input error"}});
}

void parse(Options& o, std::vector<const char*> args)
{
    args.insert(args.begin(), "checkMeshQuality");
    o.parse(static_cast<int>(args.size()), args.data());
}

} // namespace

TEST(Options, parses_flags_and_arguments)
{
    Options o = make_options();
    parse(o, {"-case", "my case", "-allGeometry"});
    EXPECT_TRUE(o.found("allGeometry"));
    EXPECT_FALSE(o.found("time"));
    EXPECT_EQ(o.get("case").value(), "my case");
    EXPECT_EQ(o.value_or("time", "latest"), "latest");
    EXPECT_EQ(o.command_line(), "checkMeshQuality -case my case -allGeometry");
}

TEST(Options, accepts_double_dash_and_inline_value)
{
    Options o = make_options();
    parse(o, {"--case=foo", "--allGeometry"});
    EXPECT_EQ(o.get("case").value(), "foo");
    EXPECT_TRUE(o.found("allGeometry"));
}

TEST(Options, unknown_option_is_a_usage_error)
{
    Options o = make_options();
    try
    {
        parse(o, {"-allGeometri"});
        FAIL() << "expected UsageError";
    }
    catch (const UsageError& e)
    {
        EXPECT_NE(std::string(e.what()).find("-allGeometri"), std::string::npos);
    }
}

TEST(Options, missing_argument_is_a_usage_error)
{
    Options o = make_options();
    EXPECT_THROW(parse(o, {"-case"}), UsageError);
    EXPECT_THROW(parse(o, {"stray"}), UsageError);
    EXPECT_THROW(parse(o, {"-case", "a", "-case", "b"}), UsageError);
}

TEST(Options, numeric_argument_may_start_with_minus)
{
    Options o = make_options();
    parse(o, {"-time", "-0.5"});
    EXPECT_EQ(o.get_scalar("time").value(), -0.5);
    parse(o, {"-time", "abc"});
    EXPECT_THROW(o.get_scalar("time"), UsageError);
}

TEST(Options, help_lists_every_option_and_exit_code)
{
    Options o = make_options();
    const std::string help = o.help_text();
    EXPECT_NE(help.find("Usage: checkMeshQuality [OPTIONS]"), std::string::npos);
    for (const OptionSpec& spec : o.specs())
        EXPECT_NE(help.find("-" + spec.name), std::string::npos) << spec.name;
    EXPECT_NE(help.find("-case <DIR>"), std::string::npos);
    EXPECT_NE(help.find("2  input error"), std::string::npos);
}

TEST(Options, parse_command_line_returns_exit_codes)
{
    Options o = make_options();
    std::ostringstream out, err;
    const log::SinkScope sink(log::stream_sink(out, err));
    const char* help[] = {"checkMeshQuality", "--help"};
    EXPECT_EQ(parse_command_line(o, 2, help, out), 0);
    EXPECT_NE(out.str().find("Usage:"), std::string::npos);
    const char* bad[] = {"checkMeshQuality", "-bogus"};
    EXPECT_EQ(parse_command_line(o, 2, bad, out), exit_input_error);
    EXPECT_EQ(err.str(), "Error: unknown option '-bogus' (see checkMeshQuality -help)\n"
                         "Usage: checkMeshQuality [OPTIONS]; see checkMeshQuality -help\n");
    const char* good[] = {"checkMeshQuality", "-allGeometry"};
    EXPECT_EQ(parse_command_line(o, 2, good, out), std::nullopt);
}

TEST(Options, argument_after_a_flag_names_the_flag_and_its_hint)
{
    Options o = make_options();
    try
    {
        parse(o, {"-allGeometry", "x"});
        FAIL() << "expected UsageError";
    }
    catch (const UsageError& e)
    {
        EXPECT_STREQ(e.what(), "unexpected argument 'x' after -allGeometry, which takes no "
                               "argument (see checkMeshQuality -help)");
    }
    std::vector<OptionSpec> specs = vtk_option_specs("checkMeshQuality", "quality fields");
    specs.push_back({"case", "DIR", "Case directory"});
    Options v("checkMeshQuality", "", specs);
    try
    {
        parse(v, {"-case", "c", "-vtk", "q.vtu"});
        FAIL() << "expected UsageError";
    }
    catch (const UsageError& e)
    {
        EXPECT_STREQ(e.what(), "unexpected argument 'q.vtu' after -vtk, which takes no argument: "
                               "-vtk writes VTK/checkMeshQuality_[<region>_]<time>.vtu in the "
                               "case; to choose the file, use -vtkFile q.vtu");
    }
}

TEST(Options, a_list_the_shell_split_gets_the_hint_to_quote_it)
{
    // morphMesh -variant 0 1 0: the shell passes three words; the option takes the first.
    Options o("morphMesh", "", {{"variant", "(a1 a2 ...)", "amplitudes"}, {"force", "", "f"}});
    for (const std::vector<const char*>& args :
         {std::vector<const char*>{"-variant", "0", "1", "0"},
          std::vector<const char*>{"-variant", "0", "-1.5", "0", "-force"}})
    {
        Options fresh = o;
        try
        {
            parse(fresh, args);
            FAIL() << "expected UsageError";
        }
        catch (const UsageError& e)
        {
            const std::string want =
                args[2] == std::string("1") ? "-variant \"(0 1 0)\"" : "-variant \"(0 -1.5 0)\"";
            EXPECT_NE(
                std::string(e.what()).find("a list goes in one quoted argument, e.g. " + want),
                std::string::npos)
                << e.what();
        }
    }
    Options quoted = o;
    parse(quoted, {"-variant", "(0 1 0)", "-force"});
    EXPECT_EQ(quoted.get("variant").value(), "(0 1 0)");
}

TEST(Options, vtk_flag_writes_into_the_case_and_vtk_file_anywhere)
{
    std::vector<OptionSpec> specs = vtk_option_specs("morphMesh", "the displacement");
    Options o("morphMesh", "", specs);
    parse(o, {});
    EXPECT_FALSE(vtk_requested(o));
    parse(o, {"-vtk"});
    EXPECT_TRUE(vtk_requested(o));
    EXPECT_TRUE(vtk_file_argument(o).empty());
    EXPECT_EQ(io::default_vtk_file("/c", "morphMesh", "", "0.5"), "/c/VTK/morphMesh_0.5.vtu");
    EXPECT_EQ(io::default_vtk_file("/c", "morphMesh", "fluid", "1"),
              "/c/VTK/morphMesh_fluid_1.vtu");
    parse(o, {"-vtkFile", "out/q.vtu"});
    EXPECT_TRUE(vtk_requested(o));
    EXPECT_EQ(vtk_file_argument(o), std::filesystem::absolute("out/q.vtu"));
    parse(o, {"-vtkFile", ""});
    EXPECT_THROW(vtk_file_argument(o), UsageError);
    const std::string help = o.help_text();
    EXPECT_NE(help.find("-vtk "), std::string::npos) << help;
    EXPECT_NE(help.find("-vtkFile <FILE>"), std::string::npos) << help;
}

TEST(RunGuarded, errors_are_logged_with_one_prefix_and_mapped_to_exit_codes)
{
    std::ostringstream out, err;
    const log::SinkScope sink(log::stream_sink(out, err));
    std::string reported;
    const FailureHook hook = [&](int, const std::string& m) { reported = m; };
    EXPECT_EQ(run_guarded([]() -> int { throw IoError("cannot read x"); }, true, hook),
              exit_input_error);
    EXPECT_EQ(err.str(), "Error: cannot read x\nNothing written.\n");
    EXPECT_EQ(reported, err.str());
    err.str("");
    EXPECT_EQ(run_guarded([]() -> int { throw SolverError("singular"); }, false), exit_fit_failed);
    EXPECT_EQ(err.str(), "Error: singular\n");
    err.str("");
    EXPECT_EQ(run_guarded([]() -> int { throw std::logic_error("bug"); }, true),
              exit_internal_error);
    EXPECT_EQ(err.str(), "Error: internal error (please report it): bug\n");
    EXPECT_EQ(run_guarded([] { return 7; }, true), 7);
    EXPECT_TRUE(out.str().empty());
}

TEST(StageTimer, logs_stage_line)
{
    const log::CaptureScope capture;
    StageTimer timer;
    const double s = timer.lap("Read mesh");
    EXPECT_GE(s, 0.0);
    EXPECT_EQ(capture.text().rfind("Read mesh in ", 0), 0u) << capture.text();
    EXPECT_EQ(format_seconds(1.234), "1.23");
    EXPECT_EQ(format_seconds(0.0042), "0.004");
    EXPECT_EQ(format_seconds(1234.4), "1234");
}
