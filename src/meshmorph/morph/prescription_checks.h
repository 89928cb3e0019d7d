// SPDX-License-Identifier: GPL-3.0-or-later
//! \file What every prescription must be before anything is fitted to it: finite, within
//! what double precision can carry, and in a 2D case within the empty planes.
//!
//! Each of these, broken, used to be written as a wrong mesh without a word: a displacement
//! of 1e300 gave non-finite points called "Mesh OK", and a translation normal to a 2D case's
//! planes was removed (OpenFOAM's 2D cases cannot move that way), leaving the points
//! unchanged. Now each is an error naming the morphDict entry (or handle) that asked for it.
#pragma once

#include <optional>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/morph/claims.h"
#include "meshmorph/morph/empty_planes.h"
#include "meshmorph/morph/morph_setup.h"

namespace meshmorph::morph
{

//! \brief The largest displacement accepted, in multiples of the mesh's bounding-box
//! diagonal. Beyond it the motion is a slip of units or digits, and the moved coordinates
//! could no longer carry the mesh's cells: a cell of 1e-4 of the mesh's size at a million
//! sizes from where it was keeps only ~6 significant digits of its own size (double
//! precision holds 16 of the coordinate), what OpenFOAM writes by default.
constexpr double max_displacement_in_mesh_sizes = 1e6;

//! \brief Refuse value claims (boundary and handle) that cannot be done: a non-finite
//! displacement, one larger than max_displacement_in_mesh_sizes times `diagonal`, and in a
//! 2D case (planes set) one with a component normal to the planes above `tolerance` (for a
//! `surface` entry: one whose motion lies wholly normal to them, the rest being the
//! target's own shape), and in an axisymmetric case one that leaves a wedge plane its point
//! lies in. Slip and free claims carry no displacement and are not checked.
//! \throw ParseError naming the dictionary, the entry's line and key (or the handle).
void check_prescriptions(const PolyMesh& mesh, const MorphSetup& setup,
                         const std::vector<Claim>& claims, const std::vector<Claim>& handle_claims,
                         const std::optional<EmptyPlanes>& planes, double diagonal,
                         double tolerance);

} // namespace meshmorph::morph
