// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/core/log.h"

#include <gtest/gtest.h>

#include <ostream>
#include <sstream>
#include <string>
#include <vector>

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

namespace
{

// Counts the flushes (sync calls) of a stream and what was written before each.
class CountingBuffer : public std::stringbuf
{
public:
    std::vector<std::string> flushed; // the text at each flush
protected:
    int sync() override
    {
        flushed.push_back(str());
        return 0;
    }
};

} // namespace

TEST(Log, stream_sink_routes_levels_and_flushes_every_line)
{
    CountingBuffer out_buf, err_buf;
    std::ostream out(&out_buf), err(&err_buf);
    const log::SinkScope scope(log::stream_sink(out, err));
    out << "report line\n"; // the application's own output, not yet flushed
    log::info() << "Read mesh";
    ASSERT_EQ(out_buf.flushed.size(), 1u);
    EXPECT_EQ(out_buf.flushed.back(), "report line\nRead mesh\n");
    log::warning() << "careful";
    // stdout is flushed before a warning, so a terminal shows both in order.
    EXPECT_EQ(out_buf.flushed.size(), 2u);
    ASSERT_EQ(err_buf.flushed.size(), 1u);
    EXPECT_EQ(err_buf.flushed.back(), "Warning: careful\n");
    log::error() << "two\nlines";
    EXPECT_EQ(err_buf.str(), "Warning: careful\nError: two\nlines\n");
    EXPECT_EQ(err_buf.flushed.size(), 2u);
    log::debug() << "hidden at the default level";
    EXPECT_EQ(out_buf.str(), "report line\nRead mesh\n");
}

TEST(Log, sink_scopes_nest_and_restore_sink_and_level)
{
    log::CaptureScope outer;
    {
        std::ostringstream out, err;
        const log::SinkScope inner(log::stream_sink(out, err));
        log::set_level(log::Level::warning);
        log::info() << "dropped";
        log::warning() << "inner";
        EXPECT_EQ(err.str(), "Warning: inner\n");
        EXPECT_TRUE(out.str().empty());
    }
    EXPECT_EQ(log::level(), log::Level::info);
    log::info() << "outer again";
    EXPECT_EQ(outer.text(), "outer again\n");
}

TEST(Exceptions, parse_error_names_file_and_line)
{
    const ParseError e("constant/polyMesh/faces", 1042, "expected '('");
    EXPECT_STREQ(e.what(), "constant/polyMesh/faces:1042: expected '('");
    EXPECT_EQ(e.line(), 1042u);
    const ParseError no_line("points", 0, "truncated binary block");
    EXPECT_STREQ(no_line.what(), "points: truncated binary block");
}
