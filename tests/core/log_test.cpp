// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/core/log.h"

#include <gtest/gtest.h>

#include "meshmorph/core/exceptions.h"

using namespace meshmorph;

TEST(Log, capture_scope_collects_levels_and_respects_level)
{
    log::CaptureScope capture;
    log::info() << "reading " << 42;
    log::warning() << "careful";
    log::debug() << "hidden";
    EXPECT_EQ(capture.text(), "reading 42\nWarning: careful\n");
    log::set_level(log::Level::debug);
    log::debug() << "shown";
    EXPECT_NE(capture.text().find("shown"), std::string::npos);
}

TEST(Exceptions, parse_error_names_file_and_line)
{
    const ParseError e("constant/polyMesh/faces", 1042, "expected '('");
    EXPECT_STREQ(e.what(), "constant/polyMesh/faces:1042: expected '('");
    EXPECT_EQ(e.line(), 1042u);
    const ParseError no_line("points", 0, "truncated binary block");
    EXPECT_STREQ(no_line.what(), "points: truncated binary block");
}
