// SPDX-License-Identifier: GPL-3.0-or-later
//! \file One fit for every design variable (morphDict `designBasis shared`, design_storage.h).
//!
//! A morph is linear in its prescription once its choices are made: the greedy RBF's centres
//! and jump marks, the IDW correction's tree and quiet nodes (deform/held_fit.h). The
//! variables of a study that constrain the same points therefore share one fit: it is chosen
//! once, on a combination of their unit prescriptions, and held; a variant is the held fit
//! applied to its prescription sum_j a_j P_j, and dJ/da_j = P_j . (its transpose applied
//! to dJ/dx). Per variable only P_j is kept, at the points it moves.
//!
//! The combination that chooses: sum_j s_j P_j / |P_j|, signs s_j = +-1 fixed by j, scaled to
//! the largest unit prescription. Equal signs would make a lattice's variables a rigid motion
//! of its patches (their B-splines sum to one) and choose centres for that motion alone;
//! mixed signs vary wherever any variable does, so the centres cover every variable.
//!
//! Linear, so without the limit (`rbf { limit yes; }` projects each field onto the ball of
//! its largest prescription, which is not linear). Serial; without wedges, cyclic patches
//! and jumpSmoothing (the transpose does not cover them yet): why_not_shared() says which.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/deform/held_fit.h"
#include "meshmorph/morph/constraint_set.h"
#include "meshmorph/morph/deformation_settings.h"

namespace meshmorph::design
{

//! A unit prescription on the shared constrained points: the rows (indices into the
//! constraints' points) where it is not zero, and its values there.
struct SparsePrescription
{
    std::vector<Index> rows;
    Points values = Points(0, 3);
};

//! The rows of `dense` (one per constrained point) that are not zero.
SparsePrescription sparse_prescription(const Points& dense);

//! Why a variable with constraints `c` cannot share the fit of one with `first` (its
//! constrained or slip points differ), or "" when it can.
std::string why_not_shared(const morph::Constraints& first, const morph::Constraints& c);
//! Why no variable of a case with constraints `c` can (a wedge, cyclic patches,
//! jumpSmoothing, -parallel), or "".
std::string why_not_shared(const morph::Constraints& c, bool parallel);

class SharedDesignFit
{
public:
    //! Chooses the fit on the combined prescription of `units` (one morph: a fit and an
    //! evaluation at every point). \param constraints the shared constraints (the first
    //! moving variable's; their displacements are replaced). \throw InvalidInput, SolverError.
    SharedDesignFit(const PolyMesh& mesh, const morph::DeformationSettings& settings,
                    morph::Constraints constraints, std::vector<SparsePrescription> units);

    //! The prescription sum_j a_j P_j, a row per constrained point.
    Points prescription(const std::vector<double>& a) const;
    //! The held fit applied to prescription (a row per constrained point): the displacement
    //! of every mesh point.
    Points apply(const Points& prescription);
    //! dJ/da_j = sum over P_j's rows of P_j . (transpose of the held map applied to g), g a
    //! row per mesh point.
    std::vector<double> transpose(const Points& g);

    const morph::Constraints& constraints() const { return constraints_; }
    const std::vector<SparsePrescription>& units() const { return units_; }
    //! The fit chosen (its centres, residual, jump constraints).
    const FitReport& report() const { return report_; }
    //! The chosen field's largest miss at the constrained points (absolute, and relative to
    //! the largest prescribed displacement): what every variant misses by, relatively.
    double max_constraint_error() const { return max_constraint_error_; }
    double relative_constraint_error() const { return relative_constraint_error_; }
    double choice_seconds() const { return choice_seconds_; }

private:
    //! The combination that chooses (see the file comment).
    Points choosing_prescription() const;

    const PolyMesh& mesh_;
    morph::Constraints constraints_;
    std::vector<SparsePrescription> units_;
    std::unique_ptr<HeldFits> held_;
    FitReport report_;
    double max_constraint_error_ = 0.0, relative_constraint_error_ = 0.0;
    double choice_seconds_ = 0.0;
};

} // namespace meshmorph::design
