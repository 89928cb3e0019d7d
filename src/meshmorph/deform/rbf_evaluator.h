// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: a fitted RBF expansion (Eq. 6) in normalised coordinates and its blocked,
//! vectorised, thread-count-independent evaluation. Never stores an n x m matrix.
#pragma once

#include <array>
#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/uniform_grid.h"

namespace meshmorph::detail
{

enum class KernelType
{
    polyharmonic, // r^power, power odd
    gaussian,     // exp(-(eps r)^2)
    multiquadric, // sqrt(1 + (eps r)^2)
    inverse_multiquadric,
    wendland_c2 // (1 - r/rho)^4_+ (4 r/rho + 1)
};

//! Kernel parameters in normalised coordinates.
struct KernelParams
{
    KernelType type = KernelType::polyharmonic;
    int power = 3;                 //!< polyharmonic exponent (odd)
    double eps = 1.0;              //!< shape parameter (normalised units)
    double support = 1.0;          //!< Wendland support radius (normalised units)
    double value(double r2) const; //!< phi as a function of r^2 (scalar reference)
    //! r2[i] := phi as a function of r2[i] for i < n: value() element by element, vectorised.
    void values_in_place(double* r2, std::size_t n) const;
};

//! d(x) = sum_j w_j phi(|x^ - c^_j|) + sum_k q_k pi_k(R^T x^), x^ = (x - centre) / scale.
struct RbfModel
{
    KernelParams kernel;
    Vector3 centre = Vector3::Zero();
    double scale = 1.0;
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); //!< polynomial frame (columns)
    std::vector<std::array<int, 3>> exponents;              //!< kept monomials
    Index num_centres = 0;
    //! Centres and weights as structure of arrays, padded to a multiple of the block with
    //! zero-weight copies of the last centre.
    std::vector<double> cx, cy, cz, wx, wy, wz;
    Eigen::Matrix<double, Eigen::Dynamic, 3> q; //!< polynomial coefficients (p x 3)
    UniformGrid grid;                           //!< Wendland only: centres by cell

    //! Normalised coordinates of physical points.
    Points normalise(const Eigen::Ref<const Points>& x) const;
    //! Sets centres (normalised, m x 3); weights are zeroed. Builds the grid for Wendland.
    void set_centres(const Eigen::Ref<const Points>& normalised_centres);
    //! Sets weights (m x 3) and polynomial coefficients (p x 3).
    void set_coefficients(const Eigen::Ref<const Eigen::MatrixXd>& w,
                          const Eigen::Ref<const Eigen::MatrixXd>& coefficients);
    //! Polynomial matrix (k x p) at normalised points.
    Eigen::MatrixXd polynomial_matrix(const Eigen::Ref<const Points>& normalised) const;
    //! Kernel matrix (k x m, column-major) between normalised points and the centres.
    Eigen::MatrixXd kernel_matrix(const Eigen::Ref<const Points>& normalised) const;
    //! d at physical points into out (n x 3). OpenMP over point blocks; deterministic.
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const;

    //! The transpose of the evaluation with respect to the coefficients: for weights G (a
    //! row per row of the physical points) K^T G (centres x 3) and P^T G (polynomial terms
    //! x 3), K and P the kernel and polynomial matrices at the points. Over pieces of points
    //! added in order: deterministic for any thread count.
    void transpose_sums(const Eigen::Ref<const Points>& points, const Eigen::Ref<const Points>& G,
                        Eigen::MatrixXd& KtG, Eigen::MatrixXd& PtG) const;

    //! The expansion as bytes (field_io.h), and back (the Wendland grid is rebuilt).
    void write(FieldWriter& out) const;
    static RbfModel read(FieldReader& in);
};

//! Monomials of total degree <= degree in 3 variables (1, x, y, z, x^2, xy, ...).
std::vector<std::array<int, 3>> monomials(int degree);

} // namespace meshmorph::detail
