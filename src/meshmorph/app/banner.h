// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The applications' banner, `End` line and per-stage timing lines.
#pragma once

#include <chrono>
#include <iosfwd>
#include <string>

#include "meshmorph/core/stopwatch.h"

namespace meshmorph::app
{

//! What the banner shows besides the build's version, date, host and PID.
struct BannerInfo
{
    std::string app_name;     //!< e.g. "checkMeshQuality"
    std::string command_line; //!< Options::command_line()
    std::string case_dir;     //!< absolute case directory (empty: not shown)
};

//! Print an OpenFOAM-like short banner:
//! ```
//! meshMorph 0.1.0 : checkMeshQuality
//! Exec   : checkMeshQuality -case cavity -allGeometry
//! Date   : Nov 21 2026
//! Time   : 06:30:00
//! Host   : myhost
//! PID    : 1234
//! Threads: 2
//! Case   : /home/me/cavity
//! ```
//! followed by an empty line, and flush `out`.
void print_banner(std::ostream& out, const BannerInfo& info);

//! Print the closing `End` line (preceded by an empty line, as OpenFOAM does).
void print_end(std::ostream& out);

//! Wall-clock stage timer: `lap("Read mesh")` logs "Read mesh in 0.42 s" (log::info; time
//! since the previous lap or construction) and returns the seconds.
class StageTimer
{
public:
    StageTimer();
    //! Log "<stage> in X s" and restart the lap clock. Returns the lap's seconds.
    double lap(const std::string& stage);
    //! Seconds since construction.
    double total() const;
    //! Seconds since the previous lap (without printing or restarting).
    double elapsed() const;

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_;
    Clock::time_point lap_start_;
};

} // namespace meshmorph::app
