// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The resolved constraint set of a morph: which points are prescribed and how
//! (values, rotations, slip projectors, cyclic pairs), with the counts the log reports.
//! A plain record: build_constraints() (constraints.h) makes it; the steps, the
//! distribution to ranks and the fit read it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/types.h"
#include "meshmorph/morph/cyclic_point_pair.h"
#include "meshmorph/morph/empty_planes.h"
#include "meshmorph/morph/morph_setup.h"
#include "meshmorph/morph/patch_assignment.h"
#include "meshmorph/morph/wedge_symmetry.h"

namespace meshmorph::morph
{

//! The resolved constraint set.
struct Constraints
{
    //! Points with a prescribed displacement (sorted mesh point indices) and their values
    //! (already without the component normal to the empty planes in 2D cases).
    std::vector<Index> points;
    Points displacements;
    //! Per entry of points: index into rotations when a rotate entry prescribes it (-1 for
    //! every other prescription), so that a morph in steps turns such points along their arc.
    std::vector<Index> rotation_of;
    std::vector<Motion> rotations;
    //! Points that slide: their displacement is P d(x) with the projector P (removes the
    //! normals of the slip/wedge planes they lie on), decided after a first fit.
    std::vector<Index> slip_points;
    std::vector<Eigen::Matrix3d> slip_projectors;
    //! Point pairs of cyclic patches that no prescription moves: their fitted displacements
    //! are averaged so that the sides stay a cyclic pair (cyclic_coupling.h).
    std::vector<CyclicPointPair> cyclic_pairs;
    //! 2D cases: the empty planes.
    std::optional<EmptyPlanes> empty_planes;
    //! Axisymmetric (two wedge patches): every displacement made axisymmetric.
    std::optional<WedgeSymmetry> wedge;

    std::vector<PatchAssignment> patches;
    //! points.size() and slip_points.size() over the whole mesh (in a -parallel run the lists
    //! hold this rank's points; the totals are those of the master).
    Index n_prescribed_points = 0;
    Index n_slip_points = 0;
    Index n_free_points = 0; //!< boundary points left unconstrained (type free)
    Index n_handle_points = 0;
    Index n_handle_overrides = 0; //!< boundary points whose prescription a handle replaced
    Index n_conflicts = 0;        //!< points with disagreeing prescriptions
    //! Points whose prescriptions differ by at most 10% of their shortest boundary edge
    //! (snapped patch edges), not counted or warned about as conflicts (see
    //! conflict_resolution.h).
    Index n_near_agreements = 0;
    double max_near_agreement = 0.0; //!< their largest difference / shortest edge
    ConflictRule conflict_rule = ConflictRule::fixed;
    JumpSmoothingMode jump_smoothing = JumpSmoothingMode::automatic; //!< MorphSetup's
    //! Patch pairs involved in conflicts, e.g. "frontWheel/lowerWall: 120 points".
    std::vector<std::string> conflict_summary;
};

} // namespace meshmorph::morph
