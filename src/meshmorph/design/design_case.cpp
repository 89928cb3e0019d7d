// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/design/design_case.h"

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/design/case_fingerprint.h"
#include "meshmorph/design/design_basis.h"
#include "meshmorph/io/decomposed_case.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/morph/deformation_dict.h"
#include "meshmorph/morph/distributed_case.h"
#include "meshmorph/morph/morph_steps.h"
#include "meshmorph/morph/new_check_failures.h"
#include "meshmorph/parallel/collective.h"

namespace meshmorph::design
{

namespace fs = std::filesystem;

fs::path design_mesh_case(const morph::MorphOptions& options)
{
    const fs::path case_dir = fs::absolute(options.case_dir).lexically_normal();
    if (!fs::is_directory(case_dir))
        throw IoError("case directory " + case_dir.string() + " does not exist");
    return options.parallel
               ? io::processor_case(case_dir, parallel::Communicator::world(), "morphMesh")
               : case_dir;
}

namespace
{

//! A pointDisplacement variable's unit motion is the field's: its bytes join the
//! dictionary's fingerprint.
void add_field_fingerprint(DesignCase& dc)
{
    if (!dc.variables.reads_point_displacement())
        return;
    const std::string time = dc.foam.time == "constant" ? "0" : dc.foam.time;
    const fs::path field = dc.mesh_case / time / dc.foam.region / "pointDisplacement";
    if (io::foam_file_exists(field))
        dc.dict_fingerprint =
            fingerprint(dc.dict_fingerprint + fingerprint(io::read_foam_file(field).data));
}

} // namespace

DesignCase read_design_case(const morph::MorphOptions& options)
{
    DesignCase dc;
    dc.case_dir = fs::absolute(options.case_dir).lexically_normal();
    dc.mesh_case = design_mesh_case(options);
    dc.parallel = options.parallel;
    fs::path dict =
        options.dict.empty() ? fs::path("system") / options.region / "morphDict" : options.dict;
    dc.dict_path = dict.is_relative() ? dc.case_dir / dict : dict;
    const io::FoamDictionary parsed = io::read_dictionary(dc.dict_path);
    dc.dict_fingerprint = dictionary_fingerprint(parsed);
    dc.setup = morph::read_morph_setup(parsed);
    // A variant is a linear combination of the variables' fields; auto's choice between the
    // smoothed and the fitted band is not linear, so design fields are not smoothed unless
    // `jumpSmoothing yes;` asks for it (linear, fields storage only).
    if (dc.setup.jump_smoothing == morph::JumpSmoothingMode::automatic)
        dc.setup.jump_smoothing = morph::JumpSmoothingMode::off;
    dc.settings = morph::read_deformation_settings(parsed, options.method);
    dc.variables = read_design_variables(parsed);
    const morph::StepSettings steps = morph::read_step_settings(parsed);
    dc.untangle = steps.untangle;
    dc.max_untangle_cells = steps.max_untangle_cells;
    dc.refuse_new_check_failures = morph::read_new_check_failures(parsed);
    dc.storage = read_design_storage(parsed);
    if (dc.variables.empty())
        throw InvalidInput(dc.dict_path.string() +
                           ": no designVariables (see tutorials/designVariables)");
    io::PolyMeshReadOptions read_options;
    read_options.time = options.time;
    read_options.region = options.region;
    const parallel::Communicator& comm = parallel::Communicator::world();
    parallel::collective(comm,
                         [&]
                         {
                             dc.foam = io::read_poly_mesh(dc.mesh_case, read_options);
                             if (dc.parallel)
                                 dc.decomposition = morph::read_decomposition(dc.foam, comm);
                         });
    dc.basis_path = design_basis_path(dc.mesh_case, options.region);
    add_field_fingerprint(dc);
    log::info() << "Read mesh from " << dc.foam.points_dir.string()
                << (dc.parallel ? " (and the other processors)" : "") << ": "
                << morph::global_count(dc.decomposition, dc.foam.mesh.n_points(), true)
                << " points, " << morph::global_count(dc.decomposition, dc.foam.mesh.n_cells, false)
                << " cells; " << dc.variables.size() << " design variables";
    return dc;
}

morph::PointDisplacementInputs read_variable_fields(const DesignCase& dc,
                                                    const morph::MorphOptions& options)
{
    if (!dc.variables.reads_point_displacement())
        return {};
    return morph::read_point_displacement(dc.mesh_case, dc.foam, options.region,
                                          parallel::Communicator::world());
}

void require_current(const DesignCase& dc, const DesignBasisHeader& header,
                     const std::string& basis_file)
{
    const auto stale = [&](const std::string& what)
    {
        return InvalidInput("the design set-up " + basis_file + " was made for " + what +
                            ": run morphMesh -variables again (nothing written; after "
                            "-overwrite the set-up's points are in points.orig)");
    };
    if (header.n_points != dc.foam.mesh.n_points())
        throw stale("a mesh of " + std::to_string(header.n_points) + " points");
    if (header.topology_fingerprint != topology_fingerprint(dc.foam.mesh))
        throw stale("another mesh topology");
    if (header.points_fingerprint != points_fingerprint(dc.foam.mesh.points))
        throw stale("other points (" + header.instance + ") than those read from " +
                    dc.foam.points_dir.string());
    if (header.dict_fingerprint != dc.dict_fingerprint)
        throw stale("another version of " + dc.dict_path.string() +
                    " (or of a file it includes, or of the pointDisplacement it reads)");
    std::vector<std::string> names;
    for (const DesignVariable& v : dc.variables.variables)
        names.push_back(v.name);
    if (names != header.names)
        throw stale("other design variables");
}

} // namespace meshmorph::design
