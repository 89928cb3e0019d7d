// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Leveled logging through a swappable sink (no initialisation needed).
//!
//! Usage: `log::info() << "Reading " << path;` — the line is emitted when the temporary
//! dies. Errors and warnings go to stderr, info and debug to stdout, unless a sink is set
//! (tests capture output that way).
#pragma once

#include <functional>
#include <memory>
#include <sstream>
#include <string>

namespace meshmorph::log
{

enum class Level
{
    error = 0,
    warning = 1,
    info = 2,
    debug = 3
};

using Sink = std::function<void(Level, const std::string&)>;

//! Replace the sink; an empty function restores the default (stdout/stderr). Thread-safe.
void set_sink(Sink sink);
//! Messages above this level are dropped (default: info).
void set_level(Level level);
Level level();
bool enabled(Level level);
//! Emit one complete message (a trailing newline is added by the default sink).
void write(Level level, const std::string& message);

//! One log line, emitted on destruction.
class Line
{
public:
    explicit Line(Level level) : level_(level), active_(enabled(level)) {}
    Line(const Line&) = delete;
    Line& operator=(const Line&) = delete;
    ~Line()
    {
        if (active_)
            write(level_, stream_.str());
    }
    template <class T> Line& operator<<(const T& value)
    {
        if (active_)
            stream_ << value;
        return *this;
    }

private:
    Level level_;
    bool active_;
    std::ostringstream stream_;
};

inline Line error()
{
    return Line(Level::error);
}
inline Line warning()
{
    return Line(Level::warning);
}
inline Line info()
{
    return Line(Level::info);
}
inline Line debug()
{
    return Line(Level::debug);
}

//! RAII: capture every message into a string while alive (for tests), restoring the sink.
class CaptureScope
{
public:
    CaptureScope();
    ~CaptureScope();
    CaptureScope(const CaptureScope&) = delete;
    CaptureScope& operator=(const CaptureScope&) = delete;
    const std::string& text() const { return *text_; }

private:
    std::shared_ptr<std::string> text_;
    Level previous_level_;
};

} // namespace meshmorph::log
