// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The MPI session of a -parallel application run, and its quiet ranks.
#pragma once

#include <optional>

#include "meshmorph/core/log.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::app
{

//! MPI for the whole run of a -parallel application; the ranks other than the master print
//! nothing (as OpenFOAM's tools). Without -parallel, nothing.
class ParallelRun
{
public:
    //! \throw Error if this build has no MPI (ParallelSession says how to get it).
    explicit ParallelRun(bool parallel);
    const parallel::Communicator& comm() const { return parallel::Communicator::world(); }
    bool master() const { return comm().master(); }

private:
    std::optional<parallel::ParallelSession> session_;
    std::optional<log::SinkScope> quiet_;
};

} // namespace meshmorph::app
