// SPDX-License-Identifier: GPL-3.0-or-later
//! \file How far a mesh can move along a straight path before a cell inverts. With the points
//! x + t dx, every face pyramid's volume is a cubic in t once the face and cell centres are
//! taken as point averages (linear in t): the face's triangles about its centre span a
//! quadratic area vector, the apex moves linearly. The first root over all pyramids and cells
//! is the step at which the first one inverts. checkMesh's own centres are area- and
//! volume-weighted (not polynomial in t), so this is an estimate, close to checkMesh's
//! verdict; design/valid_step.h confirms it with the check itself.
#pragma once

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! \brief The smallest t in (0, limit] at which a face pyramid or cell with positive volume
//! at t = 0 reaches zero volume, with the points mesh.points + t dx (point-average centres;
//! pyramids and cells not positive at t = 0 are left out: they were invalid already).
//! OpenMP over cells; the result does not depend on the thread count.
//! \param cell_faces meshmorph::cell_faces(mesh). \param dx nPoints x 3.
//! \param limit the largest step of interest (may be +infinity).
//! \return +infinity when nothing inverts within the limit.
double first_inversion_step(const PolyMesh& mesh, const CompactList& cell_faces, const Points& dx,
                            double limit);

} // namespace meshmorph
