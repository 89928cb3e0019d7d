// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Every rank's check results combined into one, as checkMesh -parallel reduces each
//! number it prints (returnReduce): counts summed, minima and maxima taken over the ranks,
//! averages from their summed parts, offender sets counted over the ranks (each rank writes
//! its own labels).
#pragma once

#include <vector>

#include "meshmorph/parallel/communicator.h"
#include "meshmorph/quality/check_result.h"

namespace meshmorph
{

//! \brief The combined results on the master (on other ranks, `mine` unchanged). A
//! collective: every rank calls it with its results of the same checks.
//! Numbers computed globally before (the region count, boundary openness, the wedge
//! geometry) are the master's.
std::vector<CheckResult> reduce_check_results(const std::vector<CheckResult>& mine,
                                              const parallel::Communicator& comm);

} // namespace meshmorph
