// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Inverse-distance weighted (Shepard) interpolation of handle displacements, the
//! explicit method of MDO Lab's IDWarp (Luke, Collins & Blades, JCP 231, 2012; Secco et al.,
//! AIAA J. 59, 2021): no linear solve, exact at the handles, and every value a convex
//! combination of the prescribed ones, so it never exceeds the largest prescription (with
//! the tree, theta > 0, up to the tree's error: ~1e-3 of the largest value).
#pragma once

#include <memory>

#include "meshmorph/deform/space_deformation.h"

namespace meshmorph
{

//! d(x) = sum_j w_j(x) h_j / sum_j w_j(x) with w_j = (L / r_j)^a + (alpha L / r_j)^b,
//! r_j = |x - x_j|, L the diagonal of the handles' bounding box.
struct IdwSettings
{
    //! a: the far-field exponent; a >= 3 makes the influence of a handle patch decay
    //! faster than the patch's apparent size grows, so far points see the whole boundary.
    int far_exponent = 3;
    //! b > a: the near-field exponent. Within about alpha^(b/(b-a)) L of the boundary the
    //! nearest handles dominate, so thin cells next to a wall move with their wall.
    int near_exponent = 5;
    double alpha = 0.2;
    //! Barnes-Hut opening ratio: a handle cluster of radius rho at distance R from a point
    //! is replaced by its second-order moment expansion when rho < theta R, decided per
    //! point (so a point's value does not depend on the points evaluated with it, nor on a
    //! -parallel decomposition). 0: direct sum (exact, for tests and small cases). The
    //! error falls like theta^3 or faster. On the snappyHexMesh motorBike (57k handles,
    //! bike lifted) the default keeps the field within 6.6e-4 of the direct sum relative to
    //! the largest displacement (4.7e-5 RMS; theta 0.25: 1.5e-3, 0.3: 3.8e-3;
    //! benchmarks/deform/idw_benchmark.cpp), as theta 0.25 did with the median-cut tree
    //! (6.1e-4) in 0.75 of its time; the test set-up of random queries around a sphere in a
    //! box is held to 2e-3 (tests/deform/idw_deformation_test.cpp). With theta > 0 and the
    //! default exponents the sums run in single precision (~1e-7 per term, far below the
    //! expansion's error); theta = 0 sums in double.
    double theta = 0.2;
};

class IdwDeformation : public SpaceDeformation
{
public:
    //! \throw InvalidInput on invalid settings.
    explicit IdwDeformation(const IdwSettings& settings = {});
    ~IdwDeformation() override;
    IdwDeformation(IdwDeformation&&) noexcept;
    IdwDeformation& operator=(IdwDeformation&&) noexcept;

    //! Builds the handle tree (O(m log m)); no solve. At a point where several handles
    //! coincide the value is one of theirs (which one is unspecified).
    void fit(const Eigen::Ref<const Points>& handles,
             const Eigen::Ref<const Points>& displacements) override;
    //! As fit(), with the handles flagged in `quiet` (one per handle, 1: quiet) quiet: the
    //! tree expands clusters of them from nearer (detail::IdwTree, quiet nodes). For the
    //! residual of a global fit, small but on the few handles the fit left out.
    void fit(const Eigen::Ref<const Points>& handles, const Eigen::Ref<const Points>& displacements,
             const std::vector<char>& quiet);
    //! fit() again at the same handles with the same quiet flags: the tree is rebuilt alike.
    void refit(const Eigen::Ref<const Points>& displacements) override;
    //! OpenMP over points; per point independent of the thread count.
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override;
    //! Exact: the transpose of the tree's sums as evaluate() takes them (idw_tree.h).
    Points transpose(const Eigen::Ref<const Points>& points,
                     const Eigen::Ref<const Points>& weights) const override;
    const FitReport& report() const override;
    bool is_fitted() const override;
    //! With a query region on `out`: only the locally essential tree (FieldKind::idw_local).
    void write_field(FieldWriter& out) const override;
    //! An IDW field written for a region (FieldKind::idw_local, the kind already read):
    //! evaluation only. \throw IoError on bad data.
    static IdwDeformation read_local(FieldReader& in);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace meshmorph
