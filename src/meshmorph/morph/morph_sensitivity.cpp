// SPDX-License-Identifier: GPL-3.0-or-later
// The reverse pass of a morph of a case (see the header).
#include "meshmorph/morph/morph_sensitivity.h"

#include <string>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/morph/deformation_methods.h"
#include "meshmorph/morph/point_morph.h"

namespace meshmorph::morph
{

namespace
{

//! What the reverse pass needs of the morph: one step (a field of the prescriptions); a
//! repair is said, not refused.
void require_one_field(const MorphResult& result)
{
    if (result.steps.empty())
        throw InvalidInput("sensitivity: morph first (the sensitivity is that of the last morph)");
    if (result.steps.size() > 1)
        throw InvalidInput("sensitivity: the last morph took " +
                           std::to_string(result.steps.size()) +
                           " steps, so its points are not one field of the prescriptions; a "
                           "smaller motion, or morphDict `steps 1;`, gives one");
    if (const UntangleReport& repair = result.steps.front().untangle; repair.invalid_before > 0)
        log::warning() << "sensitivity: the morph's repair moved " << repair.points_moved
                       << " interior points near " << repair.invalid_before
                       << " folded cells; dJ/dXs treats them as following the field (the "
                          "repair itself is not differentiated)";
    if (const NonOrthoRepair& repair = result.steps.front().non_ortho; repair.points_moved > 0)
        log::warning() << "sensitivity: the morph's repair of faces above maxNonOrtho moved "
                       << repair.points_moved << " interior points near " << repair.cells
                       << " cells; dJ/dXs treats them as following the field (the repair "
                          "itself is not differentiated)";
}

} // namespace

Points morph_sensitivity(const MorphCase& in, const MorphResult& result, const Points& dJdx,
                         const Decomposition* parts)
{
    require_one_field(result);
    const Constraints& c = result.constraints;
    const PolyMesh& mesh = in.foam.mesh;
    Constraints full = c; // the one step's constraints: the whole motion from x0
    full.displacements = prescribed_at(c, mesh.points, 1.0);
    // The smoothing as the morph applied it: `auto` may have put the fitted field back.
    full.jump_smoothing = result.steps.front().jump_smoothed_points > 0 ? JumpSmoothingMode::on
                                                                        : JumpSmoothingMode::off;
    const Points corners = bounding_corners(mesh.points, parts); // a collective: every rank
    const Index n_fit = c.n_prescribed_points + c.n_slip_points;
    const FieldMaker make = [&] { return make_deformation(in.settings, corners, n_fit); };
    return morph_points_transpose(mesh, full, make, dJdx, parts);
}

} // namespace meshmorph::morph
