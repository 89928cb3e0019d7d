// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Duplicate mesh points with different prescriptions: no smooth deformation can move
//! one position two ways, so the fit would fail on handles the user cannot map back to the
//! mesh. Caught first, naming the points file and the mesh's point labels.
#pragma once

#include <string>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/morph/constraint_set.h"

namespace meshmorph::morph
{

//! \brief Throws when two prescribed points of `mesh` have identical coordinates and
//! different displacements in `constraints`.
//! \throw InvalidInput naming `points_file`, both point labels, their position, their
//! displacements and the patches holding them.
void check_duplicate_prescribed_points(const PolyMesh& mesh, const Constraints& constraints,
                                       const std::string& points_file);

} // namespace meshmorph::morph
