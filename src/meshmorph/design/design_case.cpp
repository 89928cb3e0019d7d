// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/design/design_case.h"

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/design/case_fingerprint.h"
#include "meshmorph/design/design_basis.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/morph/deformation_dict.h"

namespace meshmorph::design
{

namespace fs = std::filesystem;

DesignCase read_design_case(const morph::MorphOptions& options)
{
    if (options.parallel)
        throw InvalidInput("-parallel is not available for design variables yet: run "
                           "-variables, -variant and -sensitivity on the undecomposed case");
    DesignCase dc;
    dc.case_dir = fs::absolute(options.case_dir).lexically_normal();
    if (!fs::is_directory(dc.case_dir))
        throw IoError("case directory " + dc.case_dir.string() + " does not exist");
    fs::path dict =
        options.dict.empty() ? fs::path("system") / options.region / "morphDict" : options.dict;
    dc.dict_path = dict.is_relative() ? dc.case_dir / dict : dict;
    const io::FoamDictionary parsed = io::read_dictionary(dc.dict_path);
    dc.dict_fingerprint = fingerprint(io::read_foam_file(dc.dict_path).data);
    dc.setup = morph::read_morph_setup(parsed);
    dc.settings = morph::read_deformation_settings(parsed, options.method);
    dc.variables = read_design_variables(parsed);
    if (dc.variables.empty())
        throw InvalidInput(dc.dict_path.string() +
                           ": no designVariables (see tutorials/designVariables)");
    io::PolyMeshReadOptions read_options;
    read_options.time = options.time;
    read_options.region = options.region;
    dc.foam = io::read_poly_mesh(dc.case_dir, read_options);
    dc.basis_path = design_basis_path(dc.case_dir, options.region);
    log::info() << "Read mesh from " << dc.foam.points_dir.string() << ": "
                << dc.foam.mesh.n_points() << " points, " << dc.foam.mesh.n_cells << " cells; "
                << dc.variables.size() << " design variables";
    return dc;
}

void require_current(const DesignCase& dc, const DesignBasisHeader& header,
                     const std::string& basis_file)
{
    const auto stale = [&](const std::string& what)
    {
        return InvalidInput("the design set-up " + basis_file + " was made for " + what +
                            ": run morphMesh -variables again (nothing written)");
    };
    if (header.topology_fingerprint != topology_fingerprint(dc.foam.mesh))
        throw stale("another mesh topology");
    if (header.points_fingerprint != points_fingerprint(dc.foam.mesh.points))
        throw stale("other points (" + header.instance + ") than those read from " +
                    dc.foam.points_dir.string());
    if (header.dict_fingerprint != dc.dict_fingerprint)
        throw stale("another version of " + dc.dict_path.string());
    std::vector<std::string> names;
    for (const DesignVariable& v : dc.variables.variables)
        names.push_back(v.name);
    if (names != header.names)
        throw stale("other design variables");
}

} // namespace meshmorph::design
