// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Faces the prescription alone folds over.
//!
//! A face whose every point is prescribed ends where the prescription puts it, whatever the
//! morph does inside the mesh. If the prescription turns it over, the boundary overlaps
//! itself there, and no method, step length or repair can unfold it. The morph says so up
//! front (a warning naming the patches) and, when its cells come out invalid, refuses with
//! the folded faces as the reason: the cause to change, where a count of invalid cells
//! only says where they are. The cell of a folded face can still come out valid (turned
//! over with it; checkMesh passes it, and halving the step found such cells on
//! oscillatingInletPeriodicAMI2D), so a fold alone is a warning, and the steps go on as
//! asked.
//!
//! Seen on OpenFOAM's windshield tutorials: a 0.5 mm glass pane 45 cells thick between the
//! cabin's walls and a fixed exterior. Scaling `walls` by 1% moves the pane's edge strips by
//! up to 8 mm, while the points the strips share with `exterior` stay put (conflict rule
//! `fixed`), 11 micrometres away: 95 strip faces fold over, and the morph was refused with
//! a count of invalid cells that did not say why.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/morph/constraint_set.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::morph
{

//! How many folded faces lie on (or touch) a patch.
struct PatchFaces
{
    std::string patch;
    Index faces = 0;
};

//! The faces the prescription folds, summed over the ranks.
struct FoldedFaces
{
    Index faces = 0;
    std::vector<PatchFaces> by_patch; //!< the patches they lie on, the most first
    //! Other patches their points lie on, the most first: where the prescription meets
    //! another, the usual cause (a moving patch beside points held still).
    std::vector<PatchFaces> meeting;
    Vector3 example = Vector3::Zero(); //!< the centre (unmoved) of the one moved the most
};

//! \brief The boundary faces whose every point `c` prescribes (slip points are not
//! prescribed) that the full prescribed motion folds over: their area vector points against
//! the unmoved one (as turned by each `rotate` entry prescribing any of their points), and
//! against that of a face beside them (sharing an edge, moved whole) that lay within 60
//! degrees of it. So a patch turned whole, however far and however prescribed, is not
//! folded; nor is a face of zero area before. A collective over `comm` (a fold whose
//! neighbour lies on another rank is left to the morph's own check).
FoldedFaces faces_folded_by_prescription(const PolyMesh& mesh, const Constraints& c,
                                         const parallel::Communicator& comm);

//! "the prescription itself folds 95 faces over: walls (95 faces), ..." with the patches
//! they meet and what to change; "" if `folded` has none.
std::string describe(const FoldedFaces& folded);

} // namespace meshmorph::morph
