// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A fitted field as bytes, and back: what evaluate() needs and nothing of the fit.
//!
//! A -parallel morph fits once (on the master rank, which gathers the constraints) and sends
//! the field to every rank, each of which evaluates it at its own points; the restored field
//! evaluates bit-identically to the original. Sizes: an RBF field is its centres, weights and
//! polynomial (6 doubles per centre), an FFD/DM-FFD field its lattice and control
//! displacements; an IDW field (method idw, or the local correction of a greedy RBF) is its
//! handles and their values (6 doubles per handle), or, written for a region, only its
//! locally essential tree: the handles near the region and the moments of the far clusters
//! (Barnes-Hut), so that a rank receives what its points need, not every handle.
#pragma once

#include <memory>
#include <string>

#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/space_deformation.h"

namespace meshmorph
{

//! \throw InvalidInput if the deformation is not fitted or its kind cannot be written.
//! \param region if given, the field evaluates exactly as the original (bit-identically)
//!        at points inside the box region->lo..hi (query_region()); elsewhere it may throw.
std::string write_field(const SpaceDeformation& deformation, const QueryRegion* region = nullptr);

//! \brief The region of the points x: their bounding box.
QueryRegion query_region(const Points& x);

//! A deformation that evaluates the written field (fit() throws: it is evaluation only).
//! \throw IoError on truncated or unknown data.
std::unique_ptr<SpaceDeformation> read_field(const std::string& bytes);

} // namespace meshmorph
