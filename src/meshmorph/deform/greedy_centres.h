// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: which constraints the greedy RBF fit (greedy_rbf_deformation.h) takes as
//! centres: farthest-point samples first, then each round a batch among those with the
//! largest residuals, never one on a jump. Choices compare coarsened values (tie_break.h),
//! so that every processor and build chooses the same centres.
#pragma once

#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/deform/greedy_settings.h"
#include "meshmorph/deform/greedy_system.h"
#include "meshmorph/deform/jump_detection.h"

namespace meshmorph::detail
{

//! Which constraints are centres, and which the factor refused (linearly dependent).
struct CentreMarks
{
    explicit CentreMarks(Eigen::Index n)
        : is_centre(std::size_t(n), 0), rejected(std::size_t(n), 0), jump(std::size_t(n), 0)
    {
    }
    std::vector<char> is_centre, rejected, jump;
};

//! Marks the constraints on a near-discontinuity of the data (detail::jump_constraints) and
//! returns the band.
JumpBand mark_jumps(const Points& X, const Eigen::MatrixXd& H, const GreedySettings& s,
                    CentreMarks& marks, Index& count);

//! The log line of the jumps left out.
void log_jumps(Index count, const JumpBand& band, const GreedySettings& s);

//! Farthest-point sampling for the initial centres, seeded by the unisolvent set U (or the
//! largest displacement when there is no polynomial); n0 centres in all. Distances equal
//! but for round-off (symmetric meshes) tie, to the lowest index.
std::vector<Eigen::Index> farthest_point_centres(const Points& X, const Eigen::MatrixXd& H,
                                                 const std::vector<Eigen::Index>& U,
                                                 Eigen::Index n0, CentreMarks& marks);

//! Adds the candidates in order; one the factor refuses is marked rejected and skipped.
void add_centres(IncrementalSystem& system, const std::vector<Eigen::Index>& candidates,
                 CentreMarks& marks);

//! |model - data| at every constraint, 0 at the jump constraints (never fitted); their
//! number left out of `n_fitted`.
Eigen::VectorXd fitted_residuals(const Points& got, const Eigen::MatrixXd& H,
                                 const CentreMarks& marks, Eigen::Index& n_fitted);

//! The constraints that may become centres: not centres yet, not refused, with a residual.
std::vector<Eigen::Index> candidates(const Eigen::VectorXd& err, const CentreMarks& marks);

//! The next round's centres among the candidates: a spread batch (GreedySettings::spread)
//! or the largest residuals, at most `room` of them.
std::vector<Eigen::Index> next_batch(std::vector<Eigen::Index> cand, const Eigen::VectorXd& err,
                                     double max_err, double max_disp, const GreedySettings& s,
                                     const Points& X, const IncrementalSystem& system,
                                     Eigen::Index centres, Eigen::Index room);

} // namespace meshmorph::detail
