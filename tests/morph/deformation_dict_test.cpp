// SPDX-License-Identifier: GPL-3.0-or-later
// The rbf keys that shape the global field: rbf.limit, rbf.greedy.spread, rbf.greedy.jumpSlope,
// rbf.greedy.jumpWidth.
#include <gtest/gtest.h>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/morph/deformation_dict.h"

namespace meshmorph::morph
{

namespace
{

DeformationSettings read(const std::string& text)
{
    return read_deformation_settings(io::parse_dictionary(text, "system/morphDict"), std::nullopt);
}

//! The message of the error reading `text` throws (empty when none).
std::string error_of(const std::string& text)
{
    try
    {
        read(text);
    }
    catch (const std::exception& e)
    {
        return e.what();
    }
    return {};
}

} // namespace

TEST(DeformationDict, the_natural_dictionary_limits_the_field_and_spreads_the_greedy_batches)
{
    const DeformationSettings s = read("method rbf;");
    EXPECT_TRUE(s.limit);
    const GreedySettings g = s.greedy.value_or(GreedySettings{}); // greedy above 5000 constraints
    EXPECT_EQ(g.spread, 1.0);
    EXPECT_EQ(g.jump_slope, 2.0);
    EXPECT_EQ(g.jump_width, 0.025);
}

TEST(DeformationDict, limit_spread_and_the_jump_band_are_read_and_zero_switches_them_off)
{
    const DeformationSettings s =
        read("method rbf;\nrbf { limit no; greedy { spread 0.5; jumpSlope 0; jumpWidth 0; } }");
    EXPECT_FALSE(s.limit);
    ASSERT_TRUE(s.greedy);
    EXPECT_EQ(s.greedy->spread, 0.5);
    EXPECT_EQ(s.greedy->jump_slope, 0.0);
    EXPECT_EQ(s.greedy->jump_width, 0.0);
    EXPECT_EQ(s.greedy->tolerance, 1e-2); // the other keys keep their defaults
}

TEST(DeformationDict, a_negative_spread_or_jump_band_and_a_bad_limit_name_their_entry)
{
    const std::string spread = error_of("method rbf;\nrbf { greedy { spread -1; } }");
    EXPECT_NE(spread.find("system/morphDict:2"), std::string::npos) << spread;
    EXPECT_NE(spread.find("spread must be >= 0"), std::string::npos) << spread;
    const std::string slope = error_of("method rbf;\nrbf {\ngreedy { jumpSlope -2; } }");
    EXPECT_NE(slope.find("system/morphDict:3"), std::string::npos) << slope;
    EXPECT_NE(slope.find("jumpSlope must be >= 0"), std::string::npos) << slope;
    const std::string width = error_of("method rbf;\nrbf { greedy {\njumpWidth -0.1; } }");
    EXPECT_NE(width.find("system/morphDict:3"), std::string::npos) << width;
    EXPECT_NE(width.find("jumpWidth must be >= 0"), std::string::npos) << width;
    const std::string limit = error_of("method rbf;\nrbf { limit maybe; }");
    EXPECT_NE(limit.find("limit"), std::string::npos) << limit;
    EXPECT_NE(limit.find("system/morphDict:2"), std::string::npos) << limit;
}

} // namespace meshmorph::morph
