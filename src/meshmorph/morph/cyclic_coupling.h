// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The two sides of a cyclic patch move alike, so that a cyclic pair stays a cyclic
//! pair (OpenFOAM matches face i of a cyclic with face i of its neighbourPatch, vertex 0
//! with vertex 0 and the others in reverse order).
//!
//! A point's partner on the other side must move by the same displacement, turned by the
//! patch's rotation for a rotational cyclic (a translational one only shifts positions):
//! - a prescribed point whose partner is not prescribed gives the partner its prescription
//!   (so the fit interpolates both sides; e.g. a free or slip cyclic next to a moving one);
//! - two prescribed partners must agree, else the dictionary is refused (naming the pair);
//! - partners that are both unprescribed (free, slip) get the mean of their fitted
//!   displacements after the evaluation (coupled_mean).
//! In a -parallel run each rank couples the cyclics it holds; a cyclic split across ranks
//! (processorCyclic) is refused: decompose with the cyclics kept whole (decomposeParDict
//! preservePatches).
#pragma once

#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/morph/constraint_set.h"
#include "meshmorph/morph/cyclic_point_pair.h"

namespace meshmorph::morph
{

//! \brief Every point pair of the mesh's cyclic (and cyclicSlip) patches with faces, each
//! once, from the owner side. Empty without cyclics.
//! \throws InvalidInput for processorCyclic patches, or cyclics that do not match.
std::vector<CyclicPointPair> cyclic_point_pairs(const PolyMesh& mesh);

//! \brief Make the prescriptions of c consistent across the pairs (see the file comment);
//! the unprescribed pairs are kept in c.cyclic_pairs for coupled_mean().
//! \param tolerance largest difference of two prescriptions that still agree.
//! \throws InvalidInput naming the patches when two partners' prescriptions differ.
void couple_cyclic_prescriptions(const PolyMesh& mesh, const std::vector<CyclicPointPair>& pairs,
                                 double tolerance, Constraints& c);

} // namespace meshmorph::morph
