// SPDX-License-Identifier: GPL-3.0-or-later
//! \file One prescription per point from its claims: agreement, conflicts and the rule.
//!
//! Claims of a point agree when their values differ by at most the agreement tolerance and
//! every value lies in every slip plane of the point (relative to the motion). A point with
//! disagreeing claims is a conflict, resolved by the `conflicts` rule: `fixed` (the default;
//! a domain wall that touches a moving body, the motorBike tyres on the ground, must stay
//! where it is) and `error` hold the point, `first`/`last` take the claim whose entry is
//! written first/last, `average` the mean of the values.
//!
//! Near agreement: snappyHexMesh leaves the points of patch edges micrometres off the
//! surfaces, so a projection moves them a little where a neighbouring patch holds or slides
//! them. Claims that differ by at most a fraction of the point's shortest boundary edge are
//! not counted or warned about as conflicts: a value that leaves a slip plane by that little
//! is projected into it; values that differ by that little still go by the rule.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "meshmorph/morph/claims.h"

namespace meshmorph::morph
{

//! The prescription of one point: a value, or a slip projector.
struct Resolved
{
    Index point = 0;
    bool is_slip = false;
    Vector3 value = Vector3::Zero();
    Eigen::Matrix3d projector = Eigen::Matrix3d::Identity(); //!< is_slip: removes the normals
    Index rotation = -1; //!< value of a rotate entry: index into the rotations
};

//! A value stays in a slip (or wedge) plane when its normal part is below this fraction of
//! it: 10x patch_plane's planarity tolerance, so a translation along a wedge's axis written
//! to 6 digits stays within both planes. Conflict resolution and the refusal of motions
//! that leave a wedge plane (prescription_checks.h) use it alike.
constexpr double in_plane_fraction = 1e-5;

struct ResolveSettings
{
    ConflictRule rule = ConflictRule::fixed;
    double agree_tolerance = 0.0;    //!< absolute
    double in_plane_tolerance = 0.0; //!< relative to the value's length
    //! Per mesh point, the length of its shortest boundary edge; null: no near agreements.
    const std::vector<double>* shortest_edges = nullptr;
    double near_agreement = 0.1; //!< fraction of the shortest edge
    //! The name of a conflict in the summary, from the point's claims (e.g. "inlet/wall").
    std::function<std::string(const std::vector<const Claim*>&)> conflict_name;
};

struct Resolution
{
    std::vector<Resolved> points; //!< sorted; points with only free claims are left out
    Index n_free = 0;             //!< points with only free claims
    Index n_conflicts = 0;
    Index n_near_agreements = 0;
    double max_near_agreement = 0.0;        //!< largest difference / shortest edge
    std::map<std::string, Index> conflicts; //!< conflict name -> number of points

    //! "<name>: <n> points" per conflict name, sorted by name.
    std::vector<std::string> conflict_summary() const;
};

//! \brief Resolve claims sorted by point (collect_claims' order).
Resolution resolve(const std::vector<Claim>& claims, const ResolveSettings& settings);

} // namespace meshmorph::morph
