// SPDX-License-Identifier: GPL-3.0-or-later
// Logging sink and level, guarded by a mutex so that OpenMP threads may log.
#include "meshmorph/core/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

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
} // namespace

void set_sink(Sink sink)
{
    std::lock_guard<std::mutex> lock(sink_mutex());
    current_sink() = std::move(sink);
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
    {
        current_sink()(l, message);
        return;
    }
    switch (l)
    {
    case Level::error:
        std::fflush(stdout);
        std::fprintf(stderr, "Error: %s\n", message.c_str());
        break;
    case Level::warning:
        std::fflush(stdout);
        std::fprintf(stderr, "Warning: %s\n", message.c_str());
        break;
    default:
        std::fprintf(stdout, "%s\n", message.c_str());
        break;
    }
}

CaptureScope::CaptureScope() : text_(std::make_shared<std::string>()), previous_level_(level())
{
    std::shared_ptr<std::string> text = text_;
    set_sink(
        [text](Level l, const std::string& m)
        {
            if (l == Level::error)
                *text += "Error: ";
            else if (l == Level::warning)
                *text += "Warning: ";
            *text += m;
            *text += '\n';
        });
}

CaptureScope::~CaptureScope()
{
    set_sink(Sink());
    set_level(previous_level_);
}

} // namespace meshmorph::log
