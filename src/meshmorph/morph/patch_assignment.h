// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Which morphDict boundary entry prescribes each patch.
//!
//! Matching follows OpenFOAM's pointDisplacement rules: exact patch name first, then a
//! patch-group name (`inGroups`, and the patch type for constraint-like types), then a
//! regex key (the last one written wins), then the `default` entry (fixed if absent). A
//! literal key that names no patch or group, and a regex that matches no patch, are errors.
//! `empty` patches keep OpenFOAM's meaning (2D: no motion normal to the planes), `wedge`
//! patches slide within their planes; naming either explicitly with a motion is an error.
//! `processor` patches are refused (decomposed cases are not supported yet).
#pragma once

#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/morph/morph_setup.h"

namespace meshmorph::morph
{

//! The prescription chosen for one patch, and why.
struct PatchAssignment
{
    std::string patch;
    std::string patch_type; //!< the patch's own type (wall, empty, ...)
    MotionType motion = MotionType::fixed;
    std::string matched_by; //!< "name", "group <g>", "regex \"...\"", "default", "empty", "wedge"
    Index entry = -1;       //!< index into MorphSetup::boundary; -1 when implicit
    Index n_points = 0;
};

//! Decide the prescription of every patch (in mesh patch order).
//! \throw ParseError (dict path + entry line) for a key matching nothing, a constraint patch
//! (empty/wedge) given another type; InvalidInput for processor patches.
//! \param decomposed processor patches are internal (matched_by "processor"), not an error.
std::vector<PatchAssignment> assign_patches(const PolyMesh& mesh, const MorphSetup& setup,
                                            bool decomposed = false);

} // namespace meshmorph::morph
