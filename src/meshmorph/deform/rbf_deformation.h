// SPDX-License-Identifier: GPL-3.0-or-later
//! \file RBF space deformation (paper Sec. 2.3, Eq. 6 and 8): exact interpolation of handle
//! displacements by radial kernels plus a low-degree polynomial.
#pragma once

#include <memory>
#include <string>

#include "meshmorph/deform/rbf_settings.h"
#include "meshmorph/deform/space_deformation.h"

namespace meshmorph
{

//! RBF deformation d(x) = sum_j w_j phi(|x - c_j|) + polynomial (Eq. 6) with centres at the
//! handles, solved exactly (Eq. 8).
//!
//! Solver (dense kernels): coordinates normalised to a unit box; polynomial basis in the
//! principal frame of the handles with degenerate terms dropped by a pivoted QR; null-space
//! reduction with the Householder QR of P (m x p): w = Q2 y, (Q2^T A Q2) y = Q2^T h; the
//! reduced matrix is definite with a kernel-dependent sign and is factored by a blocked
//! Cholesky on one thread (dense_kernels.h), its condition estimated as LAPACK's dpocon does.
//! Wendland C2: sparse SimplicialLLT of A, polynomial by the range-space (Schur complement) method.
//! Evaluation is blocked over points and centres, OpenMP-parallel and SIMD, and never
//! stores an n x m matrix.
class RbfDeformation : public SpaceDeformation
{
public:
    //! \throw InvalidInput on invalid settings (e.g. shape parameter <= 0, Wendland without
    //! support radius, a conditionally definite kernel without polynomial).
    explicit RbfDeformation(const RbfSettings& settings = {});
    ~RbfDeformation() override;
    RbfDeformation(RbfDeformation&&) noexcept;
    RbfDeformation& operator=(RbfDeformation&&) noexcept;

    //! \brief Fit to m handles (m x 3) and displacements (m x 3); exact at the handles.
    //! Coincident handles with equal displacements are merged.
    //! \throw InvalidInput (sizes, m == 0, NaN, conflicting duplicates),
    //! SolverError (factorisation failed).
    void fit(const Eigen::Ref<const Points>& handles,
             const Eigen::Ref<const Points>& displacements) override;
    //! \brief New displacements (m x 3, same handles as the last fit) reusing the
    //! factorisation: O(m^2) instead of O(m^3). Timed against the handle basis in
    //! benchmarks/paper/performance.cpp (paper Sec. 3.1). \throw InvalidInput.
    void refit(const Eigen::Ref<const Points>& displacements) override;
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override;
    //! The transpose of d(points) = B H (handle_basis) without forming B: the kernel sums
    //! at the centres times the solve's unit-displacement coefficients.
    Points transpose(const Eigen::Ref<const Points>& points,
                     const Eigen::Ref<const Points>& weights) const override;
    const FitReport& report() const override;
    bool is_fitted() const override;
    void write_field(FieldWriter& out) const override;
    //! The field at every handle of the last fit or refit (the residual report's values).
    const Points* values_at_handles() const override;
    const RbfSettings& settings() const;

    //! Centres after merging duplicates (physical coordinates, num_centres x 3).
    Points centres() const;
    //! \brief Handle basis B (k x m, m = handles given to fit) with d(points) = B H for any
    //! handle displacements H (m x 3) (paper Sec. 3.1, B = M Phi^-1). Costs O(m^3 + k m^2).
    Eigen::MatrixXd handle_basis(const Eigen::Ref<const Points>& points) const;

private:
    struct Impl;
    //! The field at the handles, kept, and the report's residuals from it.
    void report_residual(const Eigen::Ref<const Points>& displacements);
    //! The warning or error of an ill-conditioned fit (RbfSettings::condition_warning),
    //! once the residual is known.
    void check_conditioning();
    std::unique_ptr<Impl> impl_;
};

} // namespace meshmorph
