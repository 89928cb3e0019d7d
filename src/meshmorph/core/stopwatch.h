// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Wall-clock seconds since construction, and their format, for stage timings in logs
//! and reports.
#pragma once

#include <chrono>
#include <string>

namespace meshmorph
{

class Stopwatch
{
public:
    double seconds() const
    {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    void restart() { start_ = std::chrono::steady_clock::now(); }

private:
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

//! Format seconds for the stage lines: 3 significant digits, at least ms resolution
//! ("0.042", "1.23", "125").
std::string format_seconds(double seconds);

} // namespace meshmorph
