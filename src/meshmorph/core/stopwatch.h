// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Wall-clock seconds since construction, for stage timings in logs and reports.
#pragma once

#include <chrono>

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

} // namespace meshmorph
