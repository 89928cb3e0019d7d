// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A coarse global deformation made exact by a local correction: d = g + c, where g
//! is fitted first (e.g. a greedy RBF to a loose tolerance) and c interpolates g's
//! residual h_j - g(x_j) at every handle by IDW. c is exact at the handles, a convex
//! combination of the residuals everywhere (never larger than the largest one, up to the
//! IDW tree's error) and
//! dominated near each handle by its neighbours, so the handles end exactly at their
//! prescriptions without moving them alone (the hybrid RBF/IDW idea of Luke et al., JCP
//! 2012). A direct, exact g leaves a round-off residual and c does nothing visible.
//!
//! Limited (the default of morphMesh's rbf): the result is projected onto the ball of the
//! largest prescribed displacement M, d -> d min(1, M / |d|). A global RBF has no maximum
//! principle: a translated body between fixed walls pushes the points around it further
//! than itself (on the motorBike up to 2.9 times, in the wake). The projection leaves every
//! prescribed value as it is (none is larger than M), never moves a point further than M
//! and, being 1-Lipschitz, never makes the field steeper: two points move apart by no more
//! than without it.
#pragma once

#include <memory>

#include "meshmorph/deform/exact_point_index.h"
#include "meshmorph/deform/idw_deformation.h"

namespace meshmorph::detail
{
//! Projects every row of d onto the ball of radius `radius` (see CorrectedDeformation).
void limit_to_ball(Eigen::Ref<Points> d, double radius);
} // namespace meshmorph::detail

namespace meshmorph
{

class CorrectedDeformation : public SpaceDeformation
{
public:
    explicit CorrectedDeformation(std::unique_ptr<SpaceDeformation> global,
                                  const IdwSettings& correction = {}, bool limit = false);
    ~CorrectedDeformation() override;

    //! Fits the global part, evaluates its residual at the handles, fits the correction.
    //! A direct RbfDeformation whose system is numerically singular (SolverError) is
    //! replaced by a GreedyRbfDeformation with the same kernel, with a warning.
    void fit(const Eigen::Ref<const Points>& handles,
             const Eigen::Ref<const Points>& displacements) override;
    //! The global part refitted with its choices held, then the correction fitted to its
    //! residual with the fit's quiet handles: linear in the data (the limit, if set, is not:
    //! it projects onto the ball of the new data's largest prescription).
    void refit(const Eigen::Ref<const Points>& displacements) override;
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override;
    //! The global part's report; max/rms residual are those of the global part alone
    //! (what the correction takes up), max_displacement the prescriptions'.
    //! The transpose of the derivative with respect to the prescriptions: the global part's
    //! and the correction's transposes (d = g + IDW(H - g(handles))) and, limited, the
    //! projection's derivative at the fitted data.
    Points transpose(const Eigen::Ref<const Points>& points,
                     const Eigen::Ref<const Points>& weights) const override;
    const FitReport& report() const override;
    bool is_fitted() const override;
    void write_field(FieldWriter& out) const override;
    const SpaceDeformation& global() const { return *global_; }
    bool limited() const { return limit_; }

private:
    //! The global part at every row of points: at a handle of the fit its value from the
    //! fit (values_at_handles, bit for bit what its evaluation gives), elsewhere evaluated.
    void evaluate_global(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const;

    //! The correction fitted to the residual of the global part at handles_, and the report.
    void fit_correction(const Eigen::Ref<const Points>& displacements);
    //! g + c before the limit.
    void evaluate_unlimited(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const;
    //! Replaces g by the limit's transposed derivative applied to it; returns the weight
    //! that goes to M, the largest prescription's length.
    double limit_transpose(const Eigen::Ref<const Points>& points, Points& g) const;

    std::unique_ptr<SpaceDeformation> global_;
    IdwDeformation correction_;
    bool limit_ = false;
    FitReport report_;
    //! The handles of the fit and the global part's values there (empty when the global
    //! part does not keep them, or for a field read back from a file).
    detail::ExactPointIndex handle_rows_;
    Points global_at_handles_;
    //! The handles of the fit, and the row and direction of its largest prescription (what
    //! the limit's radius follows), for transpose().
    Points handles_;
    //! Per handle, quiet in the correction's tree (chosen by fit(), held by refit()).
    std::vector<char> quiet_;
    Eigen::Index largest_row_ = 0;
    Vector3 largest_direction_ = Vector3::Zero();
};

} // namespace meshmorph
