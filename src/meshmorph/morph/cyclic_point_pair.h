// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A point of a cyclic patch and its partner on the neighbour patch (cyclic_coupling.h).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/types.h"

namespace meshmorph::morph
{

//! One point of a cyclic patch and its partner on the neighbour patch.
struct CyclicPointPair
{
    Index point = -1, partner = -1;
    //! Turns a displacement of `point` into its partner's (identity for translational).
    Eigen::Matrix3d to_partner = Eigen::Matrix3d::Identity();
    Index patch = -1; //!< the patch of `point` (the owner side of the pair)
};

//! \brief The mean of each pair's displacements, in each one's frame (defined in
//! cyclic_coupling.cpp; wedge partners use it too, wedge_symmetry.h).
void coupled_mean(const std::vector<CyclicPointPair>& pairs, Points& displacement);

} // namespace meshmorph::morph
