// SPDX-License-Identifier: GPL-3.0-or-later
// Banner, End line and stage timing for the applications.
#include "meshmorph/app/banner.h"

#include <unistd.h>

#include <array>
#include <cstdio>
#include <ctime>
#include <ostream>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "meshmorph/core/config.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/stopwatch.h"

namespace meshmorph::app
{

namespace
{

std::string host_name()
{
    std::array<char, 256> buffer{};
    if (gethostname(buffer.data(), buffer.size() - 1) != 0)
        return "unknown";
    return std::string(buffer.data());
}

std::string format_time(const char* format)
{
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    std::array<char, 64> buffer{};
    const std::size_t n = std::strftime(buffer.data(), buffer.size(), format, &local);
    return std::string(buffer.data(), n);
}

} // namespace

void print_banner(std::ostream& out, const BannerInfo& info)
{
    int threads = 1;
#ifdef _OPENMP
    threads = omp_get_max_threads();
#endif
    out << "meshMorph " << MESHMORPH_VERSION << " : " << info.app_name << "\n"
        << "Exec   : " << info.command_line << "\n"
        << "Date   : " << format_time("%b %d %Y") << "\n"
        << "Time   : " << format_time("%H:%M:%S") << "\n"
        << "Host   : " << host_name() << "\n"
        << "PID    : " << getpid() << "\n"
        << "Threads: " << threads << "\n";
    if (!info.case_dir.empty())
        out << "Case   : " << info.case_dir << "\n";
    out << "\n";
    out.flush(); // shown before the first (possibly long) stage of a run redirected to a file
}

void print_end(std::ostream& out)
{
    out << "\nEnd\n\n";
    out.flush();
}

StageTimer::StageTimer() : start_(Clock::now()), lap_start_(start_) {}

double StageTimer::lap(const std::string& stage)
{
    const Clock::time_point now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - lap_start_).count();
    lap_start_ = now;
    log::info() << stage << " in " << format_seconds(seconds) << " s";
    return seconds;
}

double StageTimer::total() const
{
    return std::chrono::duration<double>(Clock::now() - start_).count();
}

double StageTimer::elapsed() const
{
    return std::chrono::duration<double>(Clock::now() - lap_start_).count();
}

} // namespace meshmorph::app
