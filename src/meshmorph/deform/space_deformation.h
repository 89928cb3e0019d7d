// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The space-deformation interface d: R^3 -> R^3 shared by RBF, FFD and DM-FFD, its fit
//! report, and apply() (x' = x + d(x), Fig. 1 of the paper).
#pragma once

#include <string>
#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph
{

class FieldWriter;
class FieldReader;

//! What a fit did; retrievable with SpaceDeformation::report() after fit().
struct FitReport
{
    std::string method;    //!< "rbf", "ffd", "dmffd", "greedy-rbf", ...
    std::string solver;    //!< factorisation used, e.g. "null-space QR + blocked Cholesky"
    Index num_handles = 0; //!< constraints after merging duplicates
    Index num_merged_duplicates = 0;
    Index num_centres = 0;      //!< RBF centres or FFD/DM-FFD control points (DoFs / 3)
    Index polynomial_terms = 0; //!< polynomial terms kept after the rank test (RBF)
    Index rank = 0;             //!< numerical rank after clamping (DM-FFD), else 0
    Index iterations = 0;       //!< refinement iterations (greedy), else 0
    //! 1-norm condition-number estimate of the factored matrix (as LAPACK's dpocon). 0: not
    //! estimated.
    //! For the sparse Wendland solve it is max(L_ii^2)/min(L_ii^2), a lower bound.
    //! For DM-FFD: sigma_max / smallest kept sigma.
    double condition_estimate = 0.0;
    double max_displacement = 0.0; //!< max |displacement| over the handles
    double max_residual = 0.0;     //!< max_i |d(h_i) - dh_i| (Euclidean), absolute
    double rms_residual = 0.0;     //!< sqrt(mean_i |d(h_i) - dh_i|^2), absolute
    //! Handles a global part leaves to a local correction (greedy RBF: jumps), and the max
    //! residual over the others (equal to max_residual when none is left out).
    Index jump_constraints = 0;
    double max_fitted_residual = 0.0;
};

//! A map d: R^3 -> R^3 fitted to prescribed handle displacements.
class SpaceDeformation
{
public:
    virtual ~SpaceDeformation() = default;
    //! \brief Fit d so that d(handles.row(i)) = displacements.row(i) (exactly for RBF, in the
    //! least-squares / least-norm sense for DM-FFD).
    //! \param handles m x 3 handle positions. \param displacements m x 3.
    //! \throw InvalidInput on size mismatch, m == 0 or non-finite input. \throw SolverError.
    virtual void fit(const Eigen::Ref<const Points>& handles,
                     const Eigen::Ref<const Points>& displacements) = 0;
    //! \brief Write d(x) for every row of points into out (n x 3). Thread-safe, deterministic
    //! (bit-identical for any number of OpenMP threads).
    //! \pre fit() was called. \throw InvalidInput if not fitted, sizes differ or a point is
    //! not finite.
    virtual void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const = 0;
    //! The report of the last fit().
    virtual const FitReport& report() const = 0;
    //! True once fit() succeeded.
    virtual bool is_fitted() const = 0;
    //! \brief Append what evaluate() needs to `out` (FieldKind first; read back by
    //! read_field() of field_io.h). \throw InvalidInput for a kind that cannot be written.
    virtual void write_field(FieldWriter& out) const;
    //! \brief The reverse pass of a sensitivity: for weights G (a row per row of points, e.g.
    //! dJ/dx) the m x 3 rows A, one per handle of the last fit(), with
    //! sum_i G_i . dd(points_i) = sum_j A_j . dH_j for every small change dH of the fitted
    //! displacements: the transpose of the fitted map's derivative with respect to its
    //! data, with the fit's choices held (greedy centres, jump flags, the IDW tree). For the
    //! linear methods that is the map itself. \throw InvalidInput for a method without it,
    //! before fit(), or on sizes.
    virtual Points transpose(const Eigen::Ref<const Points>& points,
                             const Eigen::Ref<const Points>& weights) const;
    //! \brief New displacements (m x 3) at the handles of the last fit(), every choice of that
    //! fit held (a greedy RBF's centres and jump marks, an IDW tree and its quiet nodes): the
    //! fitted field is then a linear map of its data, the one transpose() transposes. A
    //! direct RBF and DM-FFD reuse their factorisations. \throw InvalidInput before fit(), on
    //! sizes, for non-finite data or for a method without it.
    virtual void refit(const Eigen::Ref<const Points>& displacements);
    //! d at the handles of the last fit() (m x 3, bit for bit what evaluate() gives there)
    //! when the method kept them from its own residual report, else nullptr. A caller that
    //! needs them (CorrectedDeformation) then does not evaluate d at every handle again.
    virtual const Points* values_at_handles() const { return nullptr; }
    //! Per handle of the last fit(): 1 where the method left the handle to a local
    //! correction (a greedy RBF's jumps), else 0; nullptr when it leaves none out.
    virtual const std::vector<char>* handles_left_out() const { return nullptr; }
};

//! \brief d(x) for every row of points (n x 3), returned by value.
Points displacements(const SpaceDeformation& deformation, const Eigen::Ref<const Points>& points);

//! \brief x' = x + d(x) for every row of points (n x 3), returned by value.
Points apply(const SpaceDeformation& deformation, const Eigen::Ref<const Points>& points);

namespace detail
{
//! Throws InvalidInput naming `what` if any entry is NaN or infinite.
void require_finite(const Eigen::Ref<const Points>& p, const char* what);
//! Common fit() argument checks: m > 0, equal sizes, finite.
void check_fit_arguments(const Eigen::Ref<const Points>& handles,
                         const Eigen::Ref<const Points>& displacements);
//! Throws InvalidInput naming `method` unless out has a row per point.
void check_output_rows(const Eigen::Ref<const Points>& points, const Eigen::Ref<Points>& out,
                       const char* method);
//! transpose() argument checks: fitted, a finite weight row per finite point.
void check_transpose_arguments(bool is_fitted, const Eigen::Ref<const Points>& points,
                               const Eigen::Ref<const Points>& weights, const char* method);
//! Common evaluate() argument checks.
void check_evaluate_arguments(bool is_fitted, const Eigen::Ref<const Points>& points,
                              const Eigen::Ref<Points>& out, const char* method);
//! Fills max/rms residual and max displacement of report from got - displacements, got
//! being the field's values at the handles.
void residual_report(const Eigen::Ref<const Points>& got,
                     const Eigen::Ref<const Points>& displacements, FitReport& report);
//! As above with got = d(handles).
void residual_report(const SpaceDeformation& d, const Eigen::Ref<const Points>& handles,
                     const Eigen::Ref<const Points>& displacements, FitReport& report);
} // namespace detail

} // namespace meshmorph
