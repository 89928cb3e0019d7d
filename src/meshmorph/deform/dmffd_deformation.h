// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Direct-manipulation FFD (paper Sec. 2.2, Eq. 3-5): control displacements from handle
//! displacements through the clamped pseudo-inverse of the basis matrix Phi.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "meshmorph/deform/ffd_deformation.h"

namespace meshmorph
{

struct DmffdSettings
{
    FfdSettings lattice; //!< lattice resolution, box (default: handle bounds + margin), outside
    //! Singular values below clamping * sigma_max are treated as zero (Eq. 4). Default 1e-2:
    //! the paper's Fig. 8 shows 1e-10 producing wild control displacements where the handles
    //! determine the lattice poorly, while 1e-2 stays smooth. Uniform cubic B-spline
    //! collocation on well-covered lattices keeps sigma_min / sigma_max ~ 1/27 or better, so
    //! 1e-2 does not drop well-determined directions. Must be in [0, 1).
    double clamping = 1e-2;
};

//! Adaptive lattice refinement for DM-FFD by control-plane (knot) insertion (paper Sec. 3.4,
//! see DmffdDeformation::fit_refined()).
struct DmffdRefinement
{
    double tolerance = 1e-3;          //!< stop when max residual <= tolerance * max |dh|
    Index max_control_points = 20000; //!< never refine beyond this lattice size
    //! Axes that receive new control planes. The paper refines x and y only for its planar
    //! benchmark (planes across a flat direction only add useless DoFs). At least one.
    std::array<bool, 3> axes{true, true, true};
    //! Grading: after an insertion, knot spans larger than grading x an adjacent span (on a
    //! refined axis) are halved too, until none is. A point's value depends on the 4 x 4 x 4
    //! control points of the 7 spans around it; without grading a point on the edge of a
    //! finely refined cell next to a coarse one keeps its error however often its own cell is
    //! split (the refinement stalls). Must be >= 2 (halving a span must satisfy it), or 0 to
    //! switch grading off (the paper's plain insertion).
    double grading = 2.0;
};

//! One fit of DmffdDeformation::fit_refined(): the lattice and the residuals it reached.
struct DmffdRefinementStep
{
    Index control_points = 0; //!< lattice size (DoF = 3 x control_points)
    Index rank = 0;           //!< numerical rank of Phi after clamping
    double max_residual = 0.0;
    double rms_residual = 0.0;
};

//! DM-FFD: C = Phi^+ H with Phi_ij = N_j(u(h_i)) (m x n, built dense) and the pseudo-inverse
//! from LAPACK dgesdd (divide-and-conquer SVD). Least norm when under-determined, least
//! squares when over-determined; the constraint residuals are in report().
//!
//! Memory: Phi, U and V^T take 8 (m n + m r + r n) bytes, r = min(m, n), plus the SVD work
//! space (~ 8 (3 r^2 + 4 r + max(m, n)) bytes): m = 10^4 handles on a 25^3 lattice need about
//! 4 GB. Cost ~ 4 m n r flops.
class DmffdDeformation : public SpaceDeformation
{
public:
    //! \throw InvalidInput on invalid settings (clamping outside [0,1), counts < 4).
    explicit DmffdDeformation(const DmffdSettings& settings = {});

    //! \throw InvalidInput (sizes, m == 0, NaN), SolverError (SVD did not converge).
    //! Handles outside the lattice box with FfdOutside::zero cannot be matched: a warning is
    //! logged and they show up in the residuals.
    void fit(const Eigen::Ref<const Points>& handles,
             const Eigen::Ref<const Points>& displacements) override;
    //! \brief Adaptive DM-FFD (paper Sec. 3.4): fit() on the settings' lattice, then repeat
    //! { find the handle with the largest residual (among handles inside the box); on every
    //! axis enabled in refinement.axes insert a knot at the midpoint of the knot span that
    //! contains the handle's parameter (a new control plane through that lattice cell, its
    //! span halved), then grade the knot spans (see DmffdRefinement::grading); refit } until max
    //! residual <= tolerance * max |dh| or the next lattice would exceed max_control_points. Each
    //! refit is a fresh SVD of the new basis matrix (cost ~ 4 m n r per step; no SVD update). The
    //! box stays the first lattice's; the final, generally non-uniform lattice is ffd().lattice()
    //! (settings() are not changed). report().iterations counts insertions; refinement_history()
    //! has one step per fit. \throw InvalidInput (as fit(), tolerance < 0, no axis enabled),
    //! SolverError. Used by benchAdaptivity (paper Sec. 3.4, run by benchmarks/paper/
    //! deformationBenchmarks).
    void fit_refined(const Eigen::Ref<const Points>& handles,
                     const Eigen::Ref<const Points>& displacements,
                     const DmffdRefinement& refinement);
    //! Steps of the last fit_refined() (DoF, max / RMS residual per fit); empty after fit().
    const std::vector<DmffdRefinementStep>& refinement_history() const { return history_; }
    //! Whether the last fit_refined() met its tolerance (false when the budget stopped it).
    bool refinement_converged() const { return converged_; }
    //! New displacements for the same handles, reusing the SVD (O((m + n) r)). Timed against
    //! the handle basis in benchmarks/paper/performance.cpp (paper Sec. 3.1).
    void refit(const Eigen::Ref<const Points>& displacements) override;
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override;
    const FitReport& report() const override { return report_; }
    bool is_fitted() const override { return ffd_.has_value(); }
    void write_field(FieldWriter& out) const override;
    const DmffdSettings& settings() const { return settings_; }

    //! The fitted FFD (lattice and control displacements). \pre is_fitted().
    const FfdDeformation& ffd() const;
    //! Clamped pseudo-inverse Phi^+ (n x m). \pre is_fitted().
    Eigen::MatrixXd pseudo_inverse() const;
    //! Handle basis B = M Phi^+ (k x m) for points (paper Sec. 3.1). \pre is_fitted().
    Eigen::MatrixXd handle_basis(const Eigen::Ref<const Points>& points) const;

private:
    void fit_lattice(const FfdLattice& lattice, const Eigen::Ref<const Points>& handles,
                     const Eigen::Ref<const Points>& displacements);

    DmffdSettings settings_;
    std::vector<DmffdRefinementStep> history_;
    bool converged_ = false;
    std::optional<FfdDeformation> ffd_;
    Points handles_;
    Eigen::MatrixXd U_;         // m x r
    Eigen::VectorXd inv_sigma_; // r, zero where clamped
    Eigen::MatrixXd Vt_;        // r x n
    FitReport report_;
};

} // namespace meshmorph
