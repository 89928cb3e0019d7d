// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Direct-manipulation FFD (paper Sec. 2.2, Eq. 3-5): control displacements from handle
//! displacements through the clamped pseudo-inverse of the basis matrix Phi.
#pragma once

#include <optional>

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

//! Lattice refinement for DM-FFD (paper Sec. 3.4, simplified, see fit_refined()).
struct DmffdRefinement
{
    double tolerance = 1e-3;          //!< stop when max residual <= tolerance * max |dh|
    Index max_control_points = 20000; //!< never refine beyond this lattice size
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
    //! \brief fit(), then refine the lattice until the max residual is within
    //! refinement.tolerance or the next lattice would exceed max_control_points.
    //! Refinement doubles the resolution (n -> 2n - 3 control points, half the knot spacing)
    //! along the axis with the largest knot spacing, over a fixed box (the first lattice's).
    //! This is a uniform refinement, not the paper's insertion of control planes in the
    //! worst cells (which needs non-uniform knots). report().iterations counts refinements;
    //! settings().lattice.control_points holds the final resolution.
    void fit_refined(const Eigen::Ref<const Points>& handles,
                     const Eigen::Ref<const Points>& displacements,
                     const DmffdRefinement& refinement);
    //! New displacements for the same handles, reusing the SVD (O((m + n) r)).
    void refit(const Eigen::Ref<const Points>& displacements);
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override;
    const FitReport& report() const override { return report_; }
    bool is_fitted() const override { return ffd_.has_value(); }
    const DmffdSettings& settings() const { return settings_; }

    //! The fitted FFD (lattice and control displacements). \pre is_fitted().
    const FfdDeformation& ffd() const;
    //! Clamped pseudo-inverse Phi^+ (n x m). \pre is_fitted().
    Eigen::MatrixXd pseudo_inverse() const;
    //! Handle basis B = M Phi^+ (k x m) for points (paper Sec. 3.1). \pre is_fitted().
    Eigen::MatrixXd handle_basis(const Eigen::Ref<const Points>& points) const;

private:
    DmffdSettings settings_;
    std::optional<FfdDeformation> ffd_;
    Points handles_;
    Eigen::MatrixXd U_;         // m x r
    Eigen::VectorXd inv_sigma_; // r, zero where clamped
    Eigen::MatrixXd Vt_;        // r x n
    FitReport report_;
};

} // namespace meshmorph
