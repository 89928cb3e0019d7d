// SPDX-License-Identifier: GPL-3.0-or-later
//! \file How a boundary patch moves (the `type` of a morphDict boundary entry) and how
//! disagreeing prescriptions are resolved (the `conflicts` rule): the vocabulary of the
//! morphDict, with its spellings.
#pragma once

#include <string>

#include "meshmorph/core/types.h"

namespace meshmorph::morph
{

//! How a boundary patch moves.
enum class MotionType
{
    fixed,              //!< d = 0
    translate,          //!< d = vector
    rotate,             //!< rigid rotation by angle (degrees) about axis through origin
    scale,              //!< x' = origin + factor (x - origin), componentwise
    point_displacement, //!< d from <time>/pointDisplacement
    surface,            //!< d = closest point on a target surface - x
    slip,               //!< slides within its (planar) patch: tangential part of the fitted d
    free,               //!< unconstrained
};

//! Spelling of a MotionType in morphDict (`pointDisplacement`, ...).
std::string to_string(MotionType type);
//! \throw InvalidInput for an unknown spelling (message lists the valid ones).
MotionType motion_type_from_string(const std::string& word);

//! One prescription, with the parameters its type needs.
struct Motion
{
    MotionType type = MotionType::fixed;
    Vector3 vector = Vector3::Zero(); //!< translate
    Vector3 origin = Vector3::Zero(); //!< rotate, scale
    Vector3 axis = Vector3::UnitZ();  //!< rotate (need not be unit)
    double angle_degrees = 0.0;       //!< rotate
    Vector3 factor = Vector3::Ones(); //!< scale
    std::string file;                 //!< surface: path as written (relative to the case)

    //! Prescribed displacement at x for the closed-form types (fixed, translate, rotate,
    //! scale). \pre type is one of those.
    Vector3 displacement(const Vector3& x) const;
};

//! How points selected by several disagreeing prescriptions are resolved.
enum class ConflictRule
{
    error,   //!< refuse with a message naming the points' patches
    first,   //!< the entry written first in `boundary` wins
    last,    //!< the entry written last wins
    fixed,   //!< the point does not move (default)
    average, //!< mean of the prescribed displacements
};

std::string to_string(ConflictRule rule);
//! \throw InvalidInput for an unknown spelling.
ConflictRule conflict_rule_from_string(const std::string& word);

} // namespace meshmorph::morph
