// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The morphDict prescriptions as plain data (MorphSetup): the `boundary` entries,
//! the `handles` and the `conflicts` rule, read by read_morph_setup() or filled directly by
//! tests. constraints.h turns them into point constraints; the rules are documented there
//! and for users in docs/morphDict.md and `morphMesh -help`.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/morph/jump_smoothing.h"
#include "meshmorph/morph/motion.h"

namespace meshmorph::io
{
class FoamDictionary;
class FoamEntry;
} // namespace meshmorph::io

namespace meshmorph::morph
{

//! One entry of the `boundary` sub-dictionary.
struct BoundaryEntry
{
    std::string key;       //!< patch name, group name or regex as written
    bool is_regex = false; //!< key was quoted (OpenFOAM: a quoted key is a regex)
    Motion motion;
    std::size_t line = 0; //!< line in the dictionary (0 if unknown), for messages
};

//! One entry of the optional `handles` sub-dictionary (the paper's handle interface).
struct HandleEntry
{
    enum class Selection
    {
        point_zone, //!< the points of a pointZone
        box,        //!< every mesh point inside an axis-aligned box (inclusive)
        points,     //!< the mesh point nearest to each listed position
        labels,     //!< the listed mesh points (not in a morphDict: front ends' point sets)
    };
    std::string name;
    Selection selection = Selection::box;
    std::string zone;                  //!< point_zone
    Vector3 box_min = Vector3::Zero(); //!< box
    Vector3 box_max = Vector3::Zero(); //!< box
    Points points;                     //!< points: k x 3 positions
    std::vector<Index> labels;         //!< labels: distinct mesh point labels
    Points label_displacements;        //!< labels: k x 3, the displacement of each
    Vector3 displacement = Vector3::Zero();
    //! When set, the displacement at each selected point instead of `displacement` (design
    //! variables that rotate or scale a handle's points; not written in a morphDict).
    std::function<Vector3(const Vector3&)> displacement_at;
    std::size_t line = 0;
};

//! The morphDict contents that decide the constraints (deformation settings live in
//! deformation_dict.h, steps in morph_steps.h).
struct MorphSetup
{
    std::string dict_path = "system/morphDict"; //!< for messages
    //! In dictionary order; the literal key `default` is the entry for unlisted patches
    //! (fixed if absent). Order matters for the conflict rules `first` and `last`.
    std::vector<BoundaryEntry> boundary;
    std::vector<HandleEntry> handles;
    ConflictRule conflicts = ConflictRule::fixed;
    //! `jumpSmoothing auto | yes | no`: a Laplacian on the band around jumps of the
    //! prescription, kept (auto) where it lowers the band's non-orthogonality
    //! (jump_smoothing_guard.h).
    JumpSmoothingMode jump_smoothing = JumpSmoothingMode::automatic;
};

//! \brief The motion of a sub-dictionary entry { type <fixed|translate|...>; <parameters> }
//! as a boundary entry writes it; `other_keywords` may appear besides the type's own.
//! \throw ParseError naming the entry for an unknown type or keyword, a bad or non-finite value.
Motion read_motion(const io::FoamEntry& e, const std::vector<std::string>& other_keywords = {});

//! \brief Read `conflicts`, `boundary` and `handles` of a parsed morphDict.
//! Every entry is checked: an unknown top-level keyword, an entry that is not a
//! sub-dictionary, an unknown `type`, a missing or extra parameter keyword, a bad value, a
//! handle with zero or several selections. \throw ParseError naming the file, line and entry.
MorphSetup read_morph_setup(const io::FoamDictionary& dict);

} // namespace meshmorph::morph
