// SPDX-License-Identifier: GPL-3.0-or-later
//! \file How far a mesh can move along a straight path before a cell inverts. With the points
//! x + t dx, a face's area vector is quadratic in t. Let the face and cell centres start
//! where checkMesh puts them (area- and volume-weighted) and move with the average rate of
//! their points: each face pyramid's volume, (1/3) S . (Cf - Cc), is then a cubic in t, equal
//! to checkMesh's at t = 0, and so is each cell's volume, their sum. The first root over all
//! pyramids and cells estimates the step at which the first one inverts. checkMesh's centres
//! do not move linearly (their weights change with the motion), so this is an estimate;
//! design/valid_step.h confirms it with the check itself.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief The smallest t in (0, limit] at which a face pyramid or cell with positive volume
//! at t = 0 reaches zero volume, with the points mesh.points + t dx (pyramids and cells not
//! positive at t = 0 are left out: they were invalid already). OpenMP over cells; the result
//! does not depend on the thread count.
//! \param cell_faces meshmorph::cell_faces(mesh). \param geometry compute_geometry(mesh)
//! at t = 0. \param dx nPoints x 3.
//! \param limit the largest step of interest (may be +infinity).
//! \return +infinity when nothing inverts within the limit.
double first_inversion_step(const PolyMesh& mesh, const CompactList& cell_faces,
                            const MeshGeometry& geometry, const Points& dx, double limit);

//! \brief first_inversion_step per cell: for each cell (or each of `cells`, if given) the
//! first step at which it or one of its pyramids inverts (+infinity: none within `limit`).
//! A search that re-estimates from a later step can then revisit only the cells that
//! invert soonest. OpenMP over cells.
std::vector<double> cell_inversion_steps(const PolyMesh& mesh, const CompactList& cell_faces,
                                         const MeshGeometry& geometry, const Points& dx,
                                         double limit, const std::vector<Index>* cells = nullptr);

} // namespace meshmorph
