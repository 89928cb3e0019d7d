// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Classic free-form deformation (paper Sec. 2.1, Eq. 2): control point displacements
//! in, point displacements out, on a uniform cubic B-spline lattice.
#pragma once

#include <array>
#include <optional>

#include "meshmorph/deform/bspline_basis.h"
#include "meshmorph/deform/space_deformation.h"

namespace meshmorph
{

//! Lattice settings shared by FFD and DM-FFD.
struct FfdSettings
{
    //! Control points per axis (>= 4; cubic B-splines with n - 3 knot spans).
    std::array<int, 3> control_points{5, 5, 5};
    //! Explicit lattice box (parallelepiped). When empty, the box is the bounding box of the
    //! points passed to make_lattice() (for DM-FFD without box: of the handles), enlarged by
    //! margin on each side.
    std::optional<FfdBox> box;
    //! Relative enlargement of a bounding box on each side (0.01 = 1% of the extent). Points
    //! on the box itself are inside the valid domain anyway (see bspline_basis.h); the margin
    //! keeps later-evaluated points near the boundary inside too.
    double margin = 0.01;
    //! Points outside the box: zero displacement (default, classic FFD) or clamp.
    FfdOutside outside = FfdOutside::zero;
};

//! The lattice of settings: settings.box if set, else the bounding box of points + margin.
//! \throw InvalidInput (counts < 4, empty / non-finite points, degenerate box).
FfdLattice make_lattice(const FfdSettings& settings, const Eigen::Ref<const Points>& points);

//! d(x) = sum_p dc_p N_p(u(x)) (Eq. 2).
class FfdDeformation : public SpaceDeformation
{
public:
    FfdDeformation(const FfdLattice& lattice, FfdOutside outside = FfdOutside::zero);

    //! \brief Set the control point displacements directly (lattice.size() x 3).
    //! \throw InvalidInput on size mismatch or non-finite values.
    void set_control_displacements(const Eigen::Ref<const Points>& displacements);
    //! \brief SpaceDeformation::fit for FFD: handles must be the lattice's control points
    //! (lattice().control_points(), in that order, to 1e-9 of the box size); displacements
    //! are their displacements. \throw InvalidInput otherwise.
    void fit(const Eigen::Ref<const Points>& handles,
             const Eigen::Ref<const Points>& displacements) override;
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override;
    const FitReport& report() const override { return report_; }
    bool is_fitted() const override { return fitted_; }
    void write_field(FieldWriter& out) const override;

    const FfdLattice& lattice() const { return lattice_; }
    FfdOutside outside() const { return outside_; }
    const Points& control_displacements() const { return control_displacements_; }
    //! Dense basis matrix M (k x lattice.size()), M_ij = N_j(u(x_i)) (Eq. 9).
    Eigen::MatrixXd basis_matrix(const Eigen::Ref<const Points>& points) const;

private:
    FfdLattice lattice_;
    FfdOutside outside_;
    Points control_displacements_;
    FitReport report_;
    bool fitted_ = false;
};

} // namespace meshmorph
