// SPDX-License-Identifier: GPL-3.0-or-later
//! \file One fit of a space deformation to the constraints of constraints.h and its
//! evaluation at every mesh point (one step of a morph; see morph_steps.h for the steps).
//!
//! - Exactness. rbf and idw interpolate: the constrained points end at their prescriptions
//!   (round-off). DM-FFD is least squares; FFD ignores constraints (its error shows it).
//! - Slip. A first fit without the slip points gives d(x) there; its tangential part
//!   (projector of the slip planes) becomes their prescription in the final fit.
//! - 2D (empty patches). Every point, constrained or not, is fitted and evaluated at its
//!   projection onto one empty plane and the normal component removed, so both planes move
//!   identically and stay planar.
#pragma once

#include <functional>
#include <memory>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/deform/space_deformation.h"
#include "meshmorph/morph/constraint_set.h"
#include "meshmorph/morph/decomposition.h"
#include "meshmorph/morph/jump_smoothing.h"

namespace meshmorph::morph
{

//! Result of morph_points().
struct PointMorph
{
    Points displacement;     //!< nPoints x 3, d(x) for every mesh point
    Index n_constraints = 0; //!< constraints of the final fit (slip points included)
    Index n_slip = 0;
    double max_prescribed = 0.0; //!< max |prescribed displacement|
    //! max_i |displacement_i - prescribed_i| over the constrained points of the field returned
    //! (after snapping, if requested: then 0).
    double max_constraint_error = 0.0;
    double relative_constraint_error = 0.0; //!< divided by max(max_prescribed, 1e-12 diag)
    //! The fitted field's own residual max_i |d(x_i) - prescribed_i| before any snapping:
    //! round-off of an ill-conditioned direct solve, or the greedy tolerance.
    double max_fit_residual = 0.0;
    double relative_fit_residual = 0.0;
    bool snapped = false;         //!< constrained points were set to their prescriptions
    FitReport report;             //!< of the final fit
    JumpSmoothing jump_smoothing; //!< the band around jumps (jump_smoothing.h)
    double fit_seconds = 0.0;
    double evaluate_seconds = 0.0;
};

//! \brief Fit `deformation` to the constraints and evaluate it at every mesh point.
//! \param fit false: use the deformation as given (FFD with prescribed control points).
//! \param snap set the constrained points' displacements to their prescriptions after the
//! evaluation. For interpolating methods (RBF, greedy RBF) the fitted field misses them only
//! by its residual (round-off, or the greedy tolerance), so boundary points end exactly on
//! their target while the interior follows the smooth field; the residual is still reported
//! (max_fit_residual). Not for DM-FFD/FFD, whose residual is the method's least-squares error.
//! \throw InvalidInput if there are no constraints (and fit is true); SolverError.
//! \param decomposition -parallel: this rank's part; the master fits, every rank evaluates (a
//! collective: call on every rank; `deformation` is used on the master only).
PointMorph morph_points(const PolyMesh& mesh, const Constraints& constraints,
                        SpaceDeformation& deformation, bool fit = true, bool snap = false,
                        const Decomposition* decomposition = nullptr);

//! Builds a fresh, unfitted deformation (the morph's method and settings).
using FieldMaker = std::function<std::unique_ptr<SpaceDeformation>()>;

//! \brief The reverse pass of morph_points() (fit, no snapping): fits fresh deformations from
//! `make` to the constraints as morph_points() does (with slip points: the first fit that
//! gives their prescriptions, then the final one), then for weights G at every mesh point
//! (dJ/dx) returns dJ/dH at every mesh point (zero where nothing is prescribed): the
//! transpose of the fitted field's derivative with respect to the prescribed displacements,
//! the fits' choices held (SpaceDeformation::transpose). In 2D the normal component is
//! removed as the morph removes it. With a distributed decomposition (a collective): the
//! master transposes the fit of every rank's constraints at every rank's points; a shared
//! point gets the same value on every rank (also where only another rank's patch faces
//! constrain it). \throw InvalidInput for a method without a transpose, for what it does not
//! cover yet (wedges, cyclic pairs, jump smoothing) or a wrong row count; SolverError.
Points morph_points_transpose(const PolyMesh& mesh, const Constraints& c, const FieldMaker& make,
                              const Points& weights, const Decomposition* decomposition = nullptr);

//! The largest row norm of an n x 3 array (0 for none): the largest displacement.
double max_norm(const Points& values);

} // namespace meshmorph::morph
