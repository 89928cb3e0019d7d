// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal helpers shared by RbfDeformation and GreedyRbfDeformation: kernel set-up,
//! normalisation, duplicate merging, polynomial-basis choice.
#pragma once

#include <vector>

#include "meshmorph/deform/rbf_evaluator.h"
#include "meshmorph/deform/rbf_settings.h"

namespace meshmorph::detail
{

struct RbfKernelSetup
{
    KernelParams params; //!< in input units (eps, support), converted at fit time
    int degree = -1;     //!< polynomial degree, -1: none
    double sign = 1.0;   //!< sign making the reduced matrix positive definite
};

//! Validates settings. \throw InvalidInput.
RbfKernelSetup rbf_kernel_setup(const RbfSettings& settings);

struct Normalisation
{
    Vector3 centre;
    double scale = 1.0;
};
//! Bounding-box centre and largest extent (1 if all points coincide).
Normalisation normalisation_of(const Eigen::Ref<const Points>& x);

//! \brief An empty model in the normalised frame of `points` (their bounding-box centre and
//! largest extent), its kernel's shape and support scaled to that frame.
RbfModel normalised_model(const RbfKernelSetup& setup, const Eigen::Ref<const Points>& points);

struct MergedHandles
{
    Points centres;                    //!< normalised, kept handles
    Points displacements;              //!< their displacements
    std::vector<Index> representative; //!< input handle -> kept index
    std::vector<Index> first;          //!< kept index -> first input handle
};
//! Merges coincident handles (normalised distance <= tolerance) with equal displacements.
//! \throw InvalidInput naming both handles when displacements differ.
MergedHandles merge_duplicates(const Eigen::Ref<const Points>& handles,
                               const Eigen::Ref<const Points>& normalised,
                               const Eigen::Ref<const Points>& displacements, double tolerance);

//! Sets model.rotation and model.exponents: monomials up to degree in the principal frame
//! of the centres, dropping those the centres do not determine (pivoted QR).
void choose_polynomial(RbfModel& model, int degree, const Eigen::Ref<const Points>& centres,
                       double rank_tolerance);

} // namespace meshmorph::detail
