// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the option table (meshmorph/app/options.h) and the stage timer format.
#include <gtest/gtest.h>

#include <sstream>

#include "meshmorph/app/banner.h"
#include "meshmorph/app/options.h"

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
    const char* help[] = {"checkMeshQuality", "--help"};
    EXPECT_EQ(parse_command_line(o, 2, help, out, err), 0);
    EXPECT_NE(out.str().find("Usage:"), std::string::npos);
    const char* bad[] = {"checkMeshQuality", "-bogus"};
    EXPECT_EQ(parse_command_line(o, 2, bad, out, err), exit_input_error);
    EXPECT_NE(err.str().find("Error: unknown option '-bogus'"), std::string::npos);
    const char* good[] = {"checkMeshQuality", "-allGeometry"};
    EXPECT_EQ(parse_command_line(o, 2, good, out, err), std::nullopt);
}

TEST(StageTimer, prints_stage_line)
{
    std::ostringstream out;
    StageTimer timer(out);
    const double s = timer.lap("Read mesh");
    EXPECT_GE(s, 0.0);
    EXPECT_EQ(out.str().rfind("Read mesh in ", 0), 0u);
    EXPECT_EQ(format_seconds(1.234), "1.23");
    EXPECT_EQ(format_seconds(0.0042), "0.004");
    EXPECT_EQ(format_seconds(1234.4), "1234");
}
