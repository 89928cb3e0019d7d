// SPDX-License-Identifier: GPL-3.0-or-later
//! \file RAII progress report for long stages (geogram's progress.h, without singletons).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace meshmorph
{

//! Reports "  <task>: 42% (420/1000)": on a terminal redrawn on stderr at most once a
//! second; otherwise (a redirected log) as an info line at most every 2 s. Only while the
//! log level is info or higher. update() may be called from
//! any thread; only OpenMP thread 0 (or a non-OpenMP caller) prints.
class ProgressScope
{
public:
    ProgressScope(std::string task, std::int64_t total);
    ~ProgressScope();
    ProgressScope(const ProgressScope&) = delete;
    ProgressScope& operator=(const ProgressScope&) = delete;

    void update(std::int64_t done);
    //! Force progress output on or off (e.g. tests); default: auto-detect a terminal.
    static void set_enabled(bool enabled);

private:
    std::string task_;
    std::int64_t total_;
    bool active_;
    bool terminal_ = false;
    bool printed_ = false;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_;
};

} // namespace meshmorph
