// SPDX-License-Identifier: GPL-3.0-or-later
//! \file RBF space deformation (paper Sec. 2.3, Eq. 6 and 8): exact interpolation of handle
//! displacements by radial kernels plus a low-degree polynomial.
#pragma once

#include <memory>
#include <string>

#include "meshmorph/deform/space_deformation.h"

namespace meshmorph
{

//! Radial kernels phi(r) (paper Table 1).
enum class RbfKernel
{
    triharmonic,          //!< r^3 (default; Eq. 7 with k = 3, C^2)
    biharmonic,           //!< r
    polyharmonic,         //!< r^(2k-3), k = RbfSettings::polyharmonic_order >= 2
    gaussian,             //!< exp(-(eps r)^2), positive definite
    multiquadric,         //!< sqrt(1 + (eps r)^2), conditionally positive definite (order 1)
    inverse_multiquadric, //!< 1 / sqrt(1 + (eps r)^2), positive definite
    wendland_c2           //!< (1 - r/rho)^4_+ (4 r/rho + 1), compact support rho, sparse solve
};

//! "triharmonic", "biharmonic", "polyharmonic", "gaussian", "multiquadric",
//! "inverseMultiquadric", "wendlandC2".
std::string to_string(RbfKernel kernel);
//! Inverse of to_string (also accepts snake_case). \throw InvalidInput on an unknown name.
RbfKernel rbf_kernel_from_string(const std::string& name);

//! Settings of RbfDeformation; every field has a usable default.
struct RbfSettings
{
    RbfKernel kernel = RbfKernel::triharmonic;
    //! k of the polyharmonic kernel r^(2k-3) (k = 2: biharmonic, k = 3: triharmonic). The
    //! polynomial degree is max(1, k - 2) so the system stays conditionally definite.
    int polyharmonic_order = 3;
    //! eps of the Gaussian / (inverse) multiquadric kernels, in 1/length of the input
    //! coordinates (physical units). Must be > 0.
    double shape_parameter = 1.0;
    //! Wendland support radius rho in input length units. Must be > 0 for wendland_c2.
    double support_radius = 0.0;
    //! Add the polynomial (linear, Eq. 6) term. Required by the conditionally positive
    //! definite kernels (polyharmonic, multiquadric); optional for the others.
    bool polynomial = true;
    //! Handles closer than this (relative to the largest bounding-box extent) are duplicates:
    //! merged when their displacements agree to duplicate_tolerance * max |displacement|,
    //! otherwise InvalidInput.
    double duplicate_tolerance = 1e-12;
    //! Polynomial terms whose pivot in the column-normalised pivoted QR of P falls below this
    //! (relative to the largest) are dropped: coplanar / collinear handles (2D cases).
    double polynomial_rank_tolerance = 1e-9;
    //! Iterative-refinement steps after each solve (re-solve for the residual with the same
    //! factorisation, kept only while the max residual at the handles decreases). Makes the
    //! interpolation exact to round-off even at condition numbers ~1e13 (graded CFD meshes).
    int refinement_steps = 3;
    //! log::warning when the condition-number estimate exceeds this.
    double condition_warning = 1e12;
    //! Dense kernels need an m x m matrix (8 m^2 bytes: 2 GB at m = 16000). More centres
    //! than this give InvalidInput instead of an allocation failure; use the greedy RBF or
    //! the Wendland kernel for larger handle sets.
    Index max_dense_centres = 40000;
};

//! RBF deformation d(x) = sum_j w_j phi(|x - c_j|) + polynomial (Eq. 6) with centres at the
//! handles, solved exactly (Eq. 8).
//!
//! Solver (dense kernels): coordinates normalised to a unit box; polynomial basis in the
//! principal frame of the handles with degenerate terms dropped by a pivoted QR; null-space
//! reduction with the Householder QR of P (m x p): w = Q2 y, (Q2^T A Q2) y = Q2^T h; the
//! reduced matrix is definite with a kernel-dependent sign and is factored by LAPACK's
//! blocked Cholesky (dpotrf), its condition estimated by dpocon. Wendland C2: sparse
//! SimplicialLLT of A, polynomial by the range-space (Schur complement) method.
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
    void refit(const Eigen::Ref<const Points>& displacements);
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override;
    const FitReport& report() const override;
    bool is_fitted() const override;
    void write_field(FieldWriter& out) const override;
    const RbfSettings& settings() const;

    //! Centres after merging duplicates (physical coordinates, num_centres x 3).
    Points centres() const;
    //! \brief Handle basis B (k x m, m = handles given to fit) with d(points) = B H for any
    //! handle displacements H (m x 3) (paper Sec. 3.1, B = M Phi^-1). Costs O(m^3 + k m^2).
    Eigen::MatrixXd handle_basis(const Eigen::Ref<const Points>& points) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace meshmorph
