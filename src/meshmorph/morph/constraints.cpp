// SPDX-License-Identifier: GPL-3.0-or-later
// Boundary claims and handle claims, each resolved, then merged into one constraint set.
#include "meshmorph/morph/constraints.h"

#include "meshmorph/morph/cyclic_coupling.h"

#include "meshmorph/morph/constraint_steps.h"
#include "meshmorph/morph/distributed_constraints.h"
#include "meshmorph/morph/handle_selection.h"

namespace meshmorph::morph
{

Constraints build_constraints(const PolyMesh& mesh, const MorphSetup& setup,
                              const ConstraintInputs& inputs)
{
    if (inputs.decomposition != nullptr && inputs.decomposition->is_distributed())
        return build_distributed_constraints(mesh, setup, inputs, *inputs.decomposition);
    Constraints out;
    out.conflict_rule = setup.conflicts;
    out.jump_smoothing = setup.jump_smoothing;
    out.patches = inputs.patches != nullptr ? *inputs.patches : assign_patches(mesh, setup);
    out.empty_planes = find_empty_planes(mesh);
    out.wedge = find_wedge_symmetry(mesh);
    const Points corners = bounding_corners(mesh.points);
    const double agree_tol =
        detail::agreement_tolerance(corners.row(0).transpose(), corners.row(1).transpose());

    const std::vector<Claim> claims =
        collect_claims(mesh, setup, out.patches, inputs, out.empty_planes, out.rotations);
    const std::vector<Claim> handle_claims =
        collect_handle_claims(mesh, setup, out.empty_planes, agree_tol);
    const std::vector<Vector3> values = detail::resolve_and_merge(
        mesh, setup, claims, detail::shortest_boundary_edges(mesh), handle_claims, agree_tol,
        (corners.row(1) - corners.row(0)).norm(), out);
    detail::fill_displacements(values, out);
    couple_cyclic_prescriptions(mesh, cyclic_point_pairs(mesh), agree_tol, out);
    out.n_prescribed_points = static_cast<Index>(out.points.size());
    out.n_slip_points = static_cast<Index>(out.slip_points.size());
    return out;
}

} // namespace meshmorph::morph
