// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The deformation methods, one row each (rbf, idw, dmffd, ffd): the name morphDict
//! and -method use, whether the method is fitted and exact, how its deformation is made,
//! described in the log, and how much memory its fit takes. Adding a method is adding a
//! row (deformation_methods.cpp).
#pragma once

#include <memory>
#include <string>

#include "meshmorph/core/types.h"
#include "meshmorph/deform/space_deformation.h"
#include "meshmorph/morph/deformation_settings.h"
#include "meshmorph/morph/fit_memory.h"

namespace meshmorph::morph
{

std::string to_string(DeformationMethod method);
//! \throw InvalidInput for an unknown name (message lists rbf dmffd ffd idw).
DeformationMethod deformation_method_from_string(const std::string& name);

//! \brief Build the deformation for `n_constraints` constraints on a mesh with points
//! `points` (n x 3; the lattice bounds of DM-FFD / FFD default to their bounding box).
//! For FFD the control displacements are already set (no fit needed). Checks first that
//! the fit fits in memory (fit_memory.h).
//! \throw InvalidInput on invalid settings (lattice index out of range, ...).
std::unique_ptr<SpaceDeformation> make_deformation(const DeformationSettings& settings,
                                                   const Eigen::Ref<const Points>& points,
                                                   Index n_constraints);

//! Whether the deformation made by make_deformation() for these settings is fitted to the
//! constraints (false for FFD: its control points are prescribed).
bool needs_fit(const DeformationSettings& settings);
//! Whether the fitted field interpolates every constraint (rbf, idw) rather than fitting
//! it in the least-squares sense (dmffd) or ignoring it (ffd).
bool is_exact(const DeformationSettings& settings);
//! Whether the field never moves a point further than the largest prescribed displacement:
//! idw (a convex combination of the prescriptions), and rbf with its limit (`rbf { limit
//! yes; }`, the default). Only the untangling of a step can move points further then.
bool bounded_by_prescriptions(const DeformationSettings& settings);

//! Short description for the log, e.g. "rbf (triharmonic, linear polynomial, direct)".
std::string describe(const DeformationSettings& settings, Index n_constraints);

//! \brief The size of the fit of `settings` to `n_constraints` constraints: DM-FFD its
//! dense m x n basis and SVD factors, the RBF its dense systems (direct: m x m; greedy: up
//! to maxCentres squared), IDW and FFD little.
FitSize fit_size(const DeformationSettings& settings, Index n_constraints);

} // namespace meshmorph::morph
