// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The plane of a planar patch (slip and wedge patches slide within theirs).
#pragma once

#include <optional>
#include <utility>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/types.h"

namespace meshmorph::morph
{

//! Unit normal of a planar patch and its offset n.x, or nullopt if the patch is not
//! planar within `tolerance` x its bounding-box diagonal (or has no faces).
std::optional<std::pair<Vector3, double>> patch_plane(const PolyMesh& mesh, const Patch& patch,
                                                      double tolerance = 1e-6);

} // namespace meshmorph::morph
