// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/app/parallel_run.h"

namespace meshmorph::app
{

ParallelRun::ParallelRun(bool parallel)
{
    if (!parallel)
        return;
    session_.emplace();
    if (!comm().master())
        quiet_.emplace([](log::Level, const std::string&) {});
}

} // namespace meshmorph::app
