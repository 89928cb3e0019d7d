// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Whether each symmetryPlane patch is still a plane, by OpenFOAM's own test.
//!
//! OpenFOAM's symmetryPlanePolyPatch averages the unit normals of the patch's faces and
//! stops with "Symmetry plane 'P' is not planar" at any face whose unit normal differs from
//! that average by more than sqrt(SMALL) (|n - n_f|^2 > 1e-15): every tool, checkMesh
//! included, refuses to read such a mesh. A morph that moves points of a symmetryPlane
//! patch off its plane (a conflict rule giving a shared point a moving patch's
//! displacement) would otherwise write a mesh it calls fit that OpenFOAM cannot open.
#pragma once

#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph
{

//! A symmetryPlane patch OpenFOAM would refuse.
struct NonPlanarSymmetryPlane
{
    std::string patch;
    Index faces = 0;    //!< faces off the average normal, over the ranks
    double worst = 0.0; //!< the largest |n - n_f|^2
};

//! OpenFOAM's |n - n_f|^2 limit (SMALL for double precision).
constexpr double symmetry_plane_tolerance = 1e-15;

//! \brief The symmetryPlane patches of `mesh` OpenFOAM would refuse, in patch order; the
//! average normal and the counts are over the ranks of `comm` (a collective: every rank
//! holds the same patches).
std::vector<NonPlanarSymmetryPlane> non_planar_symmetry_planes(const PolyMesh& mesh,
                                                               const parallel::Communicator& comm);

} // namespace meshmorph
