// SPDX-License-Identifier: GPL-3.0-or-later
// The morph of a case, stage by stage (morph_stages.h): read (dictionary, mesh),
// constraints, check before, fit and evaluate in steps, check after, refuse or write. Every
// input error is raised in the first two stages, before anything is written.
#include "meshmorph/morph/morph_case.h"

#include <optional>
#include <utility>

#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/morph/before_check.h"
#include "meshmorph/morph/morph_log.h"
#include "meshmorph/morph/morph_stages.h"

namespace meshmorph::morph
{

MorphResult morph_case(const MorphOptions& options)
{
    MorphResult result;
    Stopwatch stage;
    MorphCase in;
    read_morph_dict(options, in, result);
    read_morph_mesh(options, in, result);
    const PolyMesh& mesh = in.foam.mesh;
    CheckMeshSettings check_settings;
    check_settings.scaled_jacobian = options.scaled_jacobian;
    check_settings.cell_fields = false;      // the report before keeps its summary only
    const CompactList cf = cell_faces(mesh); // the topology does not change: one for all checks
    const auto start_check = [&](std::optional<BeforeCheck>& c)
    { c.emplace(mesh, cf, check_settings, in.decomposition, in.foam.points_dir); };
    // The check before the morph reads only the mesh: in a serial run it starts now, on its
    // own thread, beside the constraints (which leave the mesh as it is: `in` is const
    // there). A -parallel check runs in place, so it waits until the case has been read.
    std::optional<BeforeCheck> before;
    if (!in.decomposition.is_distributed())
        start_check(before);
    resolve_constraints(options, std::as_const(in), result);
    result.output_instance = morph_output_instance(options, in);
    check_output_options(options);
    result.timings.read = stage.seconds();
    log::info() << "Read case and " << in.dict_path.string() << " in "
                << format_seconds(result.timings.read) << " s";
    log_setup(result.constraints);
    if (!before)
        start_check(before);

    std::optional<PolyMesh> moved;
    morph_resolved(options, in, cf, *before, result, moved, &in.foam.mesh);
    if (result.refused)
        return result;
    write_morph_result(options, in, *moved, result);
    return result;
}

} // namespace meshmorph::morph
