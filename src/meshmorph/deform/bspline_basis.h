// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Cubic B-spline lattices for FFD and DM-FFD (paper Sec. 2.1, Eq. 1-2), uniform or with
//! per-axis non-uniform knots (knot insertion for DM-FFD adaptivity, paper Sec. 3.4).
//!
//! A lattice of n_a >= 4 control points per axis over a parallelepiped box
//! (origin + 3 edge vectors) has n_a - 3 uniform knot spans per axis, and the box is exactly
//! the valid parameter domain [t_3, t_n] of the uniform cubic B-spline. The control points
//! sit at the Greville abscissae, one knot spacing h outside the box on each side
//! (origin - h, origin, ..., origin + edge + h), so that the undeformed lattice reproduces
//! the identity (linear precision) and points ON the box boundary are inside the domain and
//! deform with full weight (the PyGeM issue 272 failure mode cannot occur).
//!
//! Non-uniform lattices generalise this construction: per axis a strictly increasing knot
//! vector t_0 < ... < t_{n+3} (n control points, cubic, no repeated knots, i.e. "clamped-free"
//! like the uniform one), valid domain [t_3, t_n] mapped linearly onto the box, control points
//! at the Greville abscissae (t_{i+1} + t_{i+2} + t_{i+3}) / 3, so linear precision (identity
//! and affine reproduction) holds for any knot vector. The uniform lattice is the special case
//! t_j = j - 3 and keeps its closed-form fast path; other axes use Cox-de Boor recursion.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph
{

//! What an FFD does with points outside the lattice box.
enum class FfdOutside
{
    zero, //!< displacement 0 outside (classic FFD: the outside is untouched; the field is
          //!< discontinuous at the box unless the outer control layers stay fixed)
    clamp //!< use the displacement of the nearest point of the box (continuous, constant
          //!< along the outward box directions)
};

//! "zero" or "clamp". \throw InvalidInput otherwise.
FfdOutside ffd_outside_from_string(const std::string& name);
std::string to_string(FfdOutside outside);

//! Parallelepiped lattice box: x(u) = origin + axes * u, u in [0,1]^3.
struct FfdBox
{
    Vector3 origin = Vector3::Zero();
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity(); //!< columns: edge vectors
};

//! Cubic B-spline control lattice (uniform, or non-uniform per axis).
class FfdLattice
{
public:
    //! \brief Uniform lattice. \param box the valid parameter domain; \param counts control
    //! points per axis (>= 4). \throw InvalidInput on counts < 4 or a degenerate (singular /
    //! non-finite) box.
    FfdLattice(const FfdBox& box, const std::array<int, 3>& counts);
    //! \brief Lattice with explicit knot vectors: knots[a] has n_a + 4 >= 8 strictly increasing
    //! finite entries; [knots[a][3], knots[a][n_a]] is mapped onto the box edge a. An axis whose
    //! knots are exactly j - 3 uses the uniform fast path.
    //! \throw InvalidInput on short, non-finite or not strictly increasing knots, or a
    //! degenerate box.
    FfdLattice(const FfdBox& box, const std::array<std::vector<double>, 3>& knots);
    //! Axis-aligned lattice over the bounding box of points enlarged by margin * extent on
    //! each side (an extent of 0 becomes 1e-3 of the largest extent, or 1).
    //! \throw InvalidInput on empty or non-finite points, counts < 4, margin < 0.
    static FfdLattice bounding(const Eigen::Ref<const Points>& points,
                               const std::array<int, 3>& counts, double margin);

    const FfdBox& box() const { return box_; }
    const std::array<int, 3>& counts() const { return counts_; }
    //! Number of control points nx * ny * nz.
    Index size() const { return Index(counts_[0]) * counts_[1] * counts_[2]; }
    //! Linear index of control point (i, j, k): i + nx (j + ny k).
    Index index(int i, int j, int k) const { return i + counts_[0] * (j + counts_[1] * k); }
    //! Undeformed control point positions (size() x 3).
    const Points& control_points() const { return control_; }
    bool is_axis_aligned() const { return axis_aligned_; }
    //! Knot vector of axis a (n_a + 4 entries). \pre 0 <= a < 3.
    const std::vector<double>& knots(int a) const { return knots_[std::size_t(a)]; }
    //! True when axis a has the uniform knots j - 3 (closed-form basis).
    bool is_uniform(int a) const { return uniform_[std::size_t(a)]; }
    //! \brief The domain knot span [t_k, t_{k+1}] of axis a containing parameter t (t clamped
    //! to the domain [t_3, t_n]). \pre 0 <= a < 3.
    std::pair<double, double> knot_span(int a, double t) const;
    //! \brief A copy with knot t inserted on axis a (one more control plane; control points at
    //! the Greville abscissae of the new knot vector, so the copy is again an undeformed
    //! lattice reproducing the identity). \throw InvalidInput if a is not 0..2 or t is not
    //! strictly inside a domain span (at least 1e-9 of the span away from its knots).
    FfdLattice with_inserted_knot(int a, double t) const;

    //! \brief Lattice parameter t in [t_3, t_n] per axis (knot units; for a uniform lattice
    //! [0, n_a - 3], knot-span units) of x: direct for axis-aligned boxes, otherwise Newton
    //! iteration on x(t) = sum_p c_p N_p(t) started from the affine inverse (converges in one
    //! step for an undeformed parallelepiped).
    Vector3 local_coordinates(const Vector3& x) const;
    //! \brief The 64 nonzero basis values N_p(u(x)) and control indices p at x. Returns 64, or
    //! 0 for a point outside the box with FfdOutside::zero. Points within 1e-9 knot spans
    //! of the box count as inside (round-off at the boundary).
    int basis(const Vector3& x, FfdOutside outside, Index* index, double* weight) const;

private:
    void initialise(); // box checks, inverse, control points (knots_ and counts_ set)
    //! Basis values / derivatives of axis a at t (clamped to the domain).
    void axis_basis(int a, double t, int& first, double* w, double* dw) const;

    FfdBox box_;
    std::array<int, 3> counts_;
    std::array<std::vector<double>, 3> knots_;
    std::array<bool, 3> uniform_{true, true, true};
    Vector3 lo_ = Vector3::Zero(); // domain start t_3 per axis
    Vector3 hi_ = Vector3::Zero(); // domain end t_n per axis
    Eigen::Matrix3d inverse_axes_;
    bool axis_aligned_ = true;
    Points control_;
};

namespace detail
{
//! Uniform cubic B-spline values w[0..3] (and derivatives dw, may be null) at parameter t of
//! a lattice with n control points; first = index of the control point of w[0].
void cubic_bspline(double t, int n, int& first, double* w, double* dw);
//! Cubic B-spline values w[0..3] (derivatives dw, may be null) at t of the non-uniform knot
//! vector knots (Cox-de Boor, "The NURBS Book" A2.2); t is clamped to [t_3, t_n].
void cubic_bspline(double t, const std::vector<double>& knots, int& first, double* w, double* dw);
} // namespace detail

} // namespace meshmorph
