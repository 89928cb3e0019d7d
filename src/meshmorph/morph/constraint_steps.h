// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: the steps of build_constraints (constraints.h), shared by the serial
//! composition and the distributed one of a -parallel run (distributed_constraints.h).
#pragma once

#include <vector>

#include "meshmorph/morph/conflict_resolution.h"
#include "meshmorph/morph/constraint_set.h"

namespace meshmorph::morph::detail
{

//! Two prescriptions agree when they differ by less than this (1e-12 of the mesh's
//! bounding-box diagonal): far below any meaningful motion, far above round-off of the
//! closed-form motions.
double agreement_tolerance(const Vector3& lo, const Vector3& hi);

//! Per point, the length of its shortest edge on a boundary face (processor patches are not
//! boundary; infinity off the boundary).
std::vector<double> shortest_boundary_edges(const PolyMesh& mesh);

//! The boundary claims (sorted by point; `edges` indexed like their points) resolved; counts
//! and summary recorded in out. \throw InvalidInput for conflicts under rule error.
Resolution resolve_boundary(const PolyMesh& mesh, const MorphSetup& setup,
                            const std::vector<Claim>& claims, const std::vector<double>& edges,
                            double agree_tol, Constraints& out);

//! The handle claims resolved by the same rule (no near agreements: handles are explicit).
//! \throw InvalidInput for overlapping disagreeing handles under rule error.
Resolution resolve_handles(const MorphSetup& setup, const std::vector<Claim>& claims,
                           double agree_tol, Constraints& out);

//! Handles override boundary prescriptions; both sorted by point. Fills out.points,
//! rotation_of, slip_points, slip_projectors, n_handle_overrides; returns the values of
//! out.points.
std::vector<Vector3> merge(const std::vector<Resolved>& boundary,
                           const std::vector<Resolved>& handles, Constraints& out);

//! Whether any value claim is longer than tolerance.
bool any_motion(const std::vector<Claim>& claims, double tolerance);

//! A dictionary that asks for motion but resolves to none is an error (a quiet success that
//! writes unchanged points would mislead). \throw InvalidInput.
void require_some_motion(const MorphSetup& setup, bool asked, const std::vector<Vector3>& values,
                         const Constraints& out, double tolerance);

//! \brief Boundary claims and handle claims (both sorted by point, `edges` indexed like
//! their points) checked (check_prescriptions; `diagonal` the mesh's bounding box's),
//! resolved, merged (handles override), checked for motion. Returns the values
//! of out.points; counts, summary, slip points recorded in out. \throw InvalidInput.
std::vector<Vector3> resolve_and_merge(const PolyMesh& mesh, const MorphSetup& setup,
                                       const std::vector<Claim>& claims,
                                       const std::vector<double>& edges,
                                       const std::vector<Claim>& handle_claims, double agree_tol,
                                       double diagonal, Constraints& out);

//! out.displacements from the values (without their component normal to empty planes).
void fill_displacements(const std::vector<Vector3>& values, Constraints& out);

} // namespace meshmorph::morph::detail
