// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/morph/morph_log.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/core/stopwatch.h"

namespace meshmorph::morph
{

//! A mesh that already fails checks (open cells, zero-area faces, ...) is morphed (only new
//! invalid cells refuse a morph), but the user hears that the result inherits the damage.
void warn_if_broken(const QualityReport& before, const std::filesystem::path& mesh_dir)
{
    if (before.failed_checks == 0)
        return;
    std::string names;
    for (const std::string& n : before.failed_check_names)
        names += (names.empty() ? "" : ", ") + n;
    log::warning() << "the mesh in " << mesh_dir.string() << " fails " << before.failed_checks
                   << " mesh checks before the morph (" << names
                   << "); the morphed mesh keeps these defects (checkMeshQuality shows them)";
}

//! The set-up, as the user should see it: per patch its motion and why, the constraint
//! counts, conflicts and near agreements.
void log_setup(const Constraints& c)
{
    for (const PatchAssignment& a : c.patches)
        if (a.matched_by != "processor") // internal faces of the undecomposed mesh
            log::info() << "    " << a.patch << " (" << a.patch_type << ", " << a.n_points
                        << " points): " << to_string(a.motion) << "  [" << a.matched_by << "]";
    log::info() << "Constraints: " << c.n_prescribed_points << " prescribed points, "
                << c.n_slip_points << " slip points, " << c.n_free_points
                << " free boundary points, " << c.n_handle_points << " handle points"
                << (c.n_handle_overrides > 0 ? " (" + std::to_string(c.n_handle_overrides) +
                                                   " boundary points overridden by handles)"
                                             : std::string());
    if (c.empty_planes)
        log::info() << "2D case: no motion normal to the empty planes (normal "
                    << c.empty_planes->normal.transpose() << ")";
    if (c.n_conflicts > 0)
    {
        auto w = log::warning();
        w << c.n_conflicts << " points have conflicting prescriptions, resolved by rule '"
          << to_string(c.conflict_rule) << "' (set 'conflicts' in the dictionary to change):";
        for (const std::string& line : c.conflict_summary)
            w << "\n    " << line;
    }
    if (c.n_near_agreements > 0)
        log::info() << c.n_near_agreements
                    << " points shared by patches get prescriptions that differ by at most "
                    << std::lround(100.0 * c.max_near_agreement)
                    << "% of their shortest edge (as snappyHexMesh leaves patch edges slightly "
                       "off the surfaces): not conflicts; slip points keep the motion within "
                       "their plane, others follow rule '"
                    << to_string(c.conflict_rule) << "'";
}

//! The fit and the field, as the user should see them: centres, residuals, the largest
//! displacement against the largest prescribed one, the constraint error.
void log_fit(const MorphResult& result, const DeformationSettings& settings, Index n_points)
{
    const FitReport& r = result.morph.report;
    log::info() << "Fitted " << result.morph.n_constraints << " constraints with " << r.num_centres
                << (settings.method == DeformationMethod::rbf ? " centres" : " control points")
                << (r.solver.empty() ? std::string() : " (" + r.solver + ")")
                << (r.condition_estimate > 0
                        ? ", condition ~ " + format_scalar(r.condition_estimate, 3)
                        : "")
                << " in " << format_seconds(result.timings.fit) << " s";
    log::info() << "Evaluated " << n_points << " points in "
                << format_seconds(result.timings.evaluate) << " s; max displacement "
                << format_scalar(result.max_displacement, 3);
    const double rel = 1.0 / std::max(r.max_displacement, 1e-300);
    if (r.method.ends_with("+idw") && r.jump_constraints == 0)
        log::info() << "Global RBF residual " << format_scalar(r.max_residual, 3) << " ("
                    << format_scalar(r.max_residual * rel, 3)
                    << " relative), taken up by the local IDW correction";
    else if (r.method.ends_with("+idw"))
        log::info() << "Global RBF residual " << format_scalar(r.max_fitted_residual * rel, 3)
                    << " (relative) on the constraints it fits; the local IDW correction takes "
                       "up that and the "
                    << r.jump_constraints << " constraints on jumps (residual up to "
                    << format_scalar(r.max_residual * rel, 3) << ")";
    log::info() << "Largest displacement " << format_scalar(result.max_displacement, 3)
                << " (largest prescribed " << format_scalar(result.morph.max_prescribed, 3) << ")";
    // A bounded field that moved points further than its prescriptions did so in the
    // untangling, whose own line says how far; the advice below would not apply.
    if (!bounded_by_prescriptions(settings) &&
        result.max_displacement > 1.01 * result.morph.max_prescribed &&
        result.morph.max_prescribed > 0.0)
        log::warning() << "points away from the constraints move up to "
                       << format_scalar(result.max_displacement / result.morph.max_prescribed, 3)
                       << " times the largest prescribed displacement (the "
                       << to_string(settings.method)
                       << " field overshoots): rbf { limit yes; } or method idw never exceed it";
    log::info() << "Max constraint error " << format_scalar(result.morph.max_constraint_error, 3)
                << " (" << format_scalar(result.morph.relative_constraint_error, 3)
                << " of the largest prescribed displacement "
                << format_scalar(result.morph.max_prescribed, 3) << ")";
    if (is_exact(settings) && result.morph.relative_constraint_error > 1e-9)
        log::warning() << "the constrained points miss their prescriptions by up to "
                       << format_scalar(result.morph.relative_constraint_error, 3)
                       << " (relative): report this case, the field should interpolate them";
}

} // namespace meshmorph::morph
