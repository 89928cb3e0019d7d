// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Leveled logging through one swappable sink (no initialisation needed).
//!
//! Usage: `log::info() << "Reading " << path;` — the line is emitted when the temporary
//! dies. Library code reports through here only, never to std::cout/std::cerr. The
//! applications install stream_sink(out, err) for the length of a run (a SinkScope), so that
//! the log lands in the same streams as their report; without a sink, errors and warnings go
//! to stderr, info and debug to stdout. Every message is flushed as it is written: a run
//! redirected to a file (`morphMesh > log.morphMesh`) shows each line when it happens.
#pragma once

#include <functional>
#include <iosfwd>
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
//! \brief The sink applications use: info and debug lines to `out`; errors and warnings,
//! prefixed "Error: " / "Warning: ", to `err` (after flushing `out`, so that a terminal shows
//! them in order). Each message is one line (or several, for a message with newlines) and
//! is flushed. The streams must outlive the sink.
Sink stream_sink(std::ostream& out, std::ostream& err);
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

//! RAII: use `sink` while alive; then restore the previous sink and level (so a scope may
//! also change the level, e.g. an application's `-quiet`).
class SinkScope
{
public:
    explicit SinkScope(Sink sink);
    ~SinkScope();
    SinkScope(const SinkScope&) = delete;
    SinkScope& operator=(const SinkScope&) = delete;

private:
    Sink previous_sink_;
    Level previous_level_;
};

//! RAII: capture every message into a string while alive (for tests), restoring the
//! previous sink and level. Errors and warnings carry their "Error: "/"Warning: " prefix.
class CaptureScope
{
public:
    CaptureScope();
    CaptureScope(const CaptureScope&) = delete;
    CaptureScope& operator=(const CaptureScope&) = delete;
    const std::string& text() const { return *text_; }

private:
    std::shared_ptr<std::string> text_;
    SinkScope scope_;
};

} // namespace meshmorph::log
