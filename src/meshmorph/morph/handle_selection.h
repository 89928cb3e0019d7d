// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The mesh points each morphDict handle selects, as claims.
//!
//! A handle selects the points of a pointZone, every point inside a box, or the point nearest
//! to each listed position; in a 2D case the nearest in the plane of the case, on every
//! empty plane, so that a handle moves both points of a pair as the 2D motion needs.
#pragma once

#include <optional>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/morph/claims.h"
#include "meshmorph/morph/decomposition.h"
#include "meshmorph/morph/empty_planes.h"
#include "meshmorph/morph/morph_setup.h"

namespace meshmorph::morph
{

//! \brief The points `handle` selects, in selection order (a point may repeat).
//! \param tolerance 2D: points within this distance of the nearest count as nearest too.
//! \throw ParseError (dict path + handle line) for an unknown pointZone or an empty selection;
//! InvalidInput for a pointZone label out of range.
std::vector<Index> select_handle_points(const PolyMesh& mesh, const HandleEntry& handle,
                                        const std::optional<EmptyPlanes>& planes, double tolerance,
                                        const std::string& dict_path);

//! \brief One value claim per handle and selected point (source and order: the handle's
//! index), sorted by point; a handle listing a point twice claims it once.
std::vector<Claim> collect_handle_claims(const PolyMesh& mesh, const MorphSetup& setup,
                                         const std::optional<EmptyPlanes>& planes, double tolerance,
                                         const Decomposition* decomposition = nullptr);

} // namespace meshmorph::morph
