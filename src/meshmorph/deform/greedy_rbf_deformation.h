// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Greedy adaptive RBF refinement (paper Sec. 3.4, Rendall & Allen style): a few
//! centres first, then repeatedly the constraint points with the largest error.
#pragma once

#include <memory>
#include <vector>

#include "meshmorph/deform/greedy_settings.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph
{

class Stopwatch;
namespace detail
{
struct CentreMarks;
}

//! RBF deformation with greedily selected centres (a subset of the constraint points).
//!
//! The factorisation grows incrementally: the null space of the polynomial block uses the
//! Lagrange basis of a fixed polynomial-unisolvent set U (the first centres), z_j = e_j -
//! sum_{u in U} lambda_uj e_u, so adding centres only appends rows and columns to the
//! reduced matrix Z^T A Z; its Cholesky factor is extended per batch by a triangular solve
//! for the new off-diagonal block and a Cholesky of the Schur complement (dense_kernels.h),
//! never refactored from scratch. Residuals over all constraints use the blocked evaluator.
//!
//! Exactness: the result interpolates its centres exactly; the remaining constraint points
//! are met within the tolerance only. report() gives the max / RMS residual over all
//! constraints and converged() whether the tolerance was met. An application that needs
//! every constraint exact must fit RbfDeformation on all of them instead (or accept the
//! reported residual).
class GreedyRbfDeformation : public SpaceDeformation
{
public:
    //! \throw InvalidInput on invalid settings.
    explicit GreedyRbfDeformation(const GreedySettings& settings = {});
    ~GreedyRbfDeformation() override;
    GreedyRbfDeformation(GreedyRbfDeformation&&) noexcept;
    GreedyRbfDeformation& operator=(GreedyRbfDeformation&&) noexcept;

    //! \brief Greedy fit to m constraint points (m x 3) and displacements (m x 3).
    //! \throw InvalidInput (sizes, m == 0, NaN, conflicting duplicates), SolverError.
    void fit(const Eigen::Ref<const Points>& constraints,
             const Eigen::Ref<const Points>& displacements) override;
    //! The selected centres, jump marks and factor held; the centres' coefficients solved
    //! for the new data (two triangular solves) and the field evaluated at every constraint
    //! for the residual report (values_at_handles). \throw InvalidInput.
    void refit(const Eigen::Ref<const Points>& displacements) override;
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override;
    //! num_handles: constraints; num_centres: centres used; iterations; residuals over all
    //! constraints; condition_estimate: (max L_ii / min L_ii)^2, a lower bound.
    const FitReport& report() const override;
    bool is_fitted() const override;
    void write_field(FieldWriter& out) const override;
    //! The field at every constraint of the last fit (the residual report's values).
    const Points* values_at_handles() const override;
    //! The constraints on jumps (GreedySettings::jump_slope, jump_width), never centres and not
    //! fitted.
    const std::vector<char>* handles_left_out() const override;
    //! True when both tolerances were met (false when the budget stopped the refinement).
    bool converged() const;
    //! Indices (into the constraints given to fit) of the selected centres.
    const std::vector<Index>& centre_indices() const;
    //! \brief Handle basis B (k x m, m = constraints given to fit) with d(points) = B H for
    //! displacements H (m x 3) of the constraints, for the centres selected by the last fit;
    //! columns of constraints that are not centres are zero. \throw InvalidInput.
    Eigen::MatrixXd handle_basis(const Eigen::Ref<const Points>& points) const;
    //! The transpose of d(points) = B H with the centres held (handle_basis), without
    //! forming B: the kernel sums at the centres, then the transposed solve (two triangular
    //! solves with the fit's factor). Rows of constraints that are not centres are zero.
    Points transpose(const Eigen::Ref<const Points>& points,
                     const Eigen::Ref<const Points>& weights) const override;
    //! Max residual after each round (absolute), for convergence plots.
    const std::vector<double>& history() const;
    //! RMS residual after each round (absolute).
    const std::vector<double>& rms_history() const;
    //! True when the refinement stopped because a round made the RMS residual grow; the
    //! fit then keeps the centres of the best round (its residual is the smallest RMS) and
    //! history() / rms_history() end with that round (the worse one is not listed).
    bool stopped_growing() const;
    //! Constraints (after merging duplicates) left out of the fit as jumps (jump_slope,
    //! jump_width).
    Index jump_constraints() const;

private:
    struct Impl;
    //! The fit's stages (fit() runs them in order).
    void prepare(const Eigen::Ref<const Points>& constraints,
                 const Eigen::Ref<const Points>& displacements);
    void set_model(const Eigen::MatrixXd& H);
    //! Rounds until a criterion stops them; `round_values` ends as the kept model at the
    //! kept handles (Xphys), or empty when the model changed after its last evaluation.
    Eigen::Index refine(const Points& Xphys, const Eigen::MatrixXd& H, Eigen::Index budget,
                        detail::CentreMarks& marks, const Stopwatch& clock, Points& round_values);
    static Points values_at_constraints(const Impl& d, const Eigen::Ref<const Points>& constraints,
                                        const Points& round_values);
    void finish_report(const Eigen::Ref<const Points>& constraints,
                       const Eigen::Ref<const Points>& displacements, Index iterations,
                       Eigen::Index budget, const Points& round_values);
    std::unique_ptr<Impl> impl_;
};

} // namespace meshmorph
