// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The part of a decomposed mesh that this rank holds, in a -parallel run.
//!
//! decomposePar writes, per processor directory, the undecomposed mesh's label of every
//! point (constant/polyMesh/pointProcAddressing). Points on processor patches exist on
//! several ranks with identical coordinates; their global label identifies them, so that a
//! shared point counts once in the constraints and gets one prescription.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/types.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::morph
{

struct Decomposition
{
    const parallel::Communicator* comm = nullptr;
    std::vector<Index> global_point;  //!< per local point, its label in the undecomposed mesh
    std::vector<Index> shared_points; //!< local points on processor patches (sorted)

    bool is_distributed() const { return comm != nullptr && comm->is_parallel(); }
};

//! \brief This rank's part: its point labels (pointProcAddressing) and its shared points.
Decomposition make_decomposition(const PolyMesh& mesh, std::vector<Index> global_point,
                                 const parallel::Communicator& comm);

//! The corners (2 x 3: min, max) of the bounding box of x; with a distributed decomposition,
//! of every rank's points (a collective), alike on every rank.
Points bounding_corners(const Points& x, const Decomposition* decomposition = nullptr);

} // namespace meshmorph::morph
