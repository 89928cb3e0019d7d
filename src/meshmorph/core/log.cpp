// SPDX-License-Identifier: GPL-3.0-or-later
// Logging sink and level, guarded by a mutex so that OpenMP threads may log.
#include "meshmorph/core/log.h"

#include <atomic>
#include <iostream>
#include <mutex>
#include <utility>

namespace meshmorph::log
{
namespace
{
std::mutex& sink_mutex()
{
    static std::mutex m;
    return m;
}
Sink& current_sink()
{
    static Sink s;
    return s;
}
std::atomic<int>& current_level()
{
    static std::atomic<int> l{static_cast<int>(Level::info)};
    return l;
}

const char* prefix(Level l)
{
    switch (l)
    {
    case Level::error:
        return "Error: ";
    case Level::warning:
        return "Warning: ";
    default:
        return "";
    }
}

// One message as a line on `out` (info, debug) or `err` (errors, warnings), flushed. The
// line is one write: std::cerr is unbuffered, and under mpirun (or `2>&1` to a pipe) the
// prefix written apart could land in another line of the other stream.
void write_line(std::ostream& out, std::ostream& err, Level l, const std::string& message)
{
    if (l == Level::error || l == Level::warning)
    {
        out.flush();
        err << (prefix(l) + message + '\n');
        err.flush();
        return;
    }
    out << (message + '\n');
    out.flush();
}
} // namespace

void set_sink(Sink sink)
{
    std::lock_guard<std::mutex> lock(sink_mutex());
    current_sink() = std::move(sink);
}

Sink stream_sink(std::ostream& out, std::ostream& err)
{
    return [&out, &err](Level l, const std::string& message) { write_line(out, err, l, message); };
}

void set_level(Level level)
{
    current_level() = static_cast<int>(level);
}

Level level()
{
    return static_cast<Level>(current_level().load());
}

bool enabled(Level l)
{
    return static_cast<int>(l) <= current_level().load();
}

void write(Level l, const std::string& message)
{
    std::lock_guard<std::mutex> lock(sink_mutex());
    if (current_sink())
        current_sink()(l, message);
    else
        write_line(std::cout, std::cerr, l, message);
}

SinkScope::SinkScope(Sink sink) : previous_level_(level())
{
    std::lock_guard<std::mutex> lock(sink_mutex());
    previous_sink_ = std::exchange(current_sink(), std::move(sink));
}

SinkScope::~SinkScope()
{
    {
        std::lock_guard<std::mutex> lock(sink_mutex());
        current_sink() = std::move(previous_sink_);
    }
    set_level(previous_level_);
}

CaptureScope::CaptureScope()
    : text_(std::make_shared<std::string>()), scope_(
                                                  [text = text_](Level l, const std::string& m)
                                                  {
                                                      *text += prefix(l);
                                                      *text += m;
                                                      *text += '\n';
                                                  })
{
}

} // namespace meshmorph::log
