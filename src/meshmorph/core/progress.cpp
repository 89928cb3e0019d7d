// SPDX-License-Identifier: GPL-3.0-or-later
// Progress output on stderr, throttled to about one line per second.
#include "meshmorph/core/progress.h"

#include <atomic>
#include <cstdio>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "meshmorph/core/log.h"

namespace meshmorph
{
namespace
{
// -1: auto-detect, 0: off, 1: on.
std::atomic<int> forced{-1};
} // namespace

void ProgressScope::set_enabled(bool enabled)
{
    forced = enabled ? 1 : 0;
}

ProgressScope::ProgressScope(std::string task, std::int64_t total)
    : task_(std::move(task)), total_(total), start_(std::chrono::steady_clock::now()), last_(start_)
{
    const int f = forced.load();
    terminal_ = isatty(STDERR_FILENO) != 0;
    active_ = f == 1 || (f == -1 && log::enabled(log::Level::info));
}

ProgressScope::~ProgressScope()
{
    if (active_ && printed_ && terminal_)
        std::fprintf(stderr, "\r  %s: done%30s\n", task_.c_str(), "");
}

void ProgressScope::update(std::int64_t done)
{
    if (!active_)
        return;
#ifdef _OPENMP
    if (omp_get_thread_num() != 0)
        return;
#endif
    const auto now = std::chrono::steady_clock::now();
    // A terminal gets a line redrawn every second; a log file a line every 2 s.
    if (now - last_ < std::chrono::seconds(terminal_ ? 1 : 2))
        return;
    last_ = now;
    printed_ = true;
    const double pct = total_ > 0 ? 100.0 * static_cast<double>(done) / total_ : 0.0;
    if (!terminal_)
    {
        log::info() << "    " << task_ << ": " << static_cast<int>(pct) << "% (" << done << "/"
                    << total_ << ")";
        return;
    }
    // Redrawing one line in place is terminal control, not a log line, so it writes to the
    // terminal itself; anywhere else progress is the log line above.
    std::fprintf(stderr, "\r  %s: %3.0f%% (%lld/%lld)", task_.c_str(), pct,
                 static_cast<long long>(done), static_cast<long long>(total_));
    std::fflush(stderr);
}

} // namespace meshmorph
