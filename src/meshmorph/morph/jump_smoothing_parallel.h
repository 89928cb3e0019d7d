// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The jump smoothing of a -parallel morph: each rank's part of the band's graph on the
//! master, which solves the band's Laplacian as a serial morph does (jump_band_graph.h) and
//! sends each rank the values of its points. The band is a few thousand points on the
//! motorBike (3,300 at a 5% lift), so one process solves it in hundredths of a second.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/morph/decomposition.h"
#include "meshmorph/morph/jump_smoothing.h"

namespace meshmorph::morph
{

//! \brief smooth_jumps on a decomposed mesh (a collective). \param mesh, x_eval this rank's
//! points and where the field is evaluated; \param constrained, positions, values the
//! gathered prescription on the master (labels of the undecomposed mesh, ascending; empty
//! on the other ranks); \param displacement this rank's field, changed on its band points.
//! The report (counts, width) is the same on every rank; `band` and `fitted` are this
//! rank's points. A point shared by ranks gets the same value on each.
JumpSmoothing smooth_jumps_distributed(const PolyMesh& mesh, const Points& x_eval,
                                       const Decomposition& d,
                                       const std::vector<Index>& constrained,
                                       const Points& positions, const Points& values,
                                       Points& displacement);

} // namespace meshmorph::morph
