// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The part of a decomposed mesh that this rank holds, in a -parallel run.
//!
//! decomposePar writes, per processor directory, the undecomposed mesh's label of every
//! point (constant/polyMesh/pointProcAddressing). Points on processor patches exist on
//! several ranks with identical coordinates; their global label identifies them, so that a
//! shared point counts once in the constraints and gets one prescription.
#pragma once

#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::morph
{

struct Decomposition
{
    const parallel::Communicator* comm = nullptr;
    std::vector<Index> global_point; //!< per local point, its label in the undecomposed mesh

    bool is_distributed() const { return comm != nullptr && comm->is_parallel(); }
};

} // namespace meshmorph::morph
