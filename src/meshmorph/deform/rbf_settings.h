// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The settings of an RBF deformation: the radial kernel (paper Table 1) and the
//! solver's options. Plain records, shared by the direct and the greedy RBF.
#pragma once

#include <string>

#include "meshmorph/core/types.h"

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
    //! log::warning when the condition-number estimate exceeds this and the fit shows it:
    //! the largest residual at the handles is above residual_warning times the largest
    //! displacement. Graded CFD meshes reach condition numbers ~1e13-1e14 (the 2D airFoil2D
    //! tutorial 8e13) and iterative refinement still fits them to ~1e-9; 1e-6 is below the
    //! six significant digits OpenFOAM writes points with by default, so a fit within it is
    //! exact for the mesh, and a warning there would be one the user can do nothing about.
    double condition_warning = 1e12;
    double residual_warning = 1e-6;
    //! SolverError instead of the warning above, for a caller with a better fit to fall back
    //! on (morphMesh's `method rbf` takes the greedy RBF, whose centres stay apart).
    bool ill_conditioning_is_error = false;
    //! Dense kernels need an m x m matrix (8 m^2 bytes: 2 GB at m = 16000). More centres
    //! than this give InvalidInput instead of an allocation failure; use the greedy RBF or
    //! the Wendland kernel for larger handle sets.
    Index max_dense_centres = 40000;
};

} // namespace meshmorph
