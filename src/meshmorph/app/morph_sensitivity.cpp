// SPDX-License-Identifier: GPL-3.0-or-later
// -sensitivity without design variables: the morph's reverse pass, written as a point field.
#include "meshmorph/app/morph_sensitivity.h"

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <utility>

#include "meshmorph/app/exit_status.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/design/design_sensitivity.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/point_field_writer.h"
#include "meshmorph/morph/morph_log.h"
#include "meshmorph/morph/morph_sensitivity.h"
#include "meshmorph/parallel/collective.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::app
{

namespace fs = std::filesystem;

namespace
{

//! The morphDict and the mesh, as morphMesh reads them.
void read_case(const morph::MorphOptions& options, morph::MorphCase& in, morph::MorphResult& result)
{
    morph::read_morph_dict(options, in, result);
    morph::read_morph_mesh(options, in, result);
}

//! dJ/dx, read before the morph so that a bad file fails at once. With -parallel each rank
//! reads its processor directory's file, as decomposePar writes it.
Points read_dJdx(const morph::MorphCase& in, const fs::path& input)
{
    Points dJdx;
    parallel::collective(parallel::Communicator::world(),
                         [&] { dJdx = design::read_point_sensitivity(in.foam.mesh, input); });
    return dJdx;
}

//! The morphDict's morph of the case read, in memory (as morphMesh runs it, nothing
//! written); `in` keeps the mesh as read.
void morph_in_memory(const morph::MorphOptions& options, morph::MorphCase& in,
                     morph::MorphResult& result)
{
    morph::resolve_constraints(options, std::as_const(in), result);
    morph::log_setup(result.constraints);
    const CompactList cf = cell_faces(in.foam.mesh);
    CheckMeshSettings check;
    check.scaled_jacobian = false;
    check.cell_fields = false;
    morph::BeforeCheck before(in.foam.mesh, cf, check, in.decomposition, in.foam.points_dir);
    std::optional<PolyMesh> moved;
    morph::morph_resolved(options, in, cf, before, result, moved);
    if (result.refused)
        log::warning() << "the morph itself is refused (" << result.refusal
                       << "); dJ/dXs is still that of its field";
}

} // namespace

bool declares_design_variables(const morph::MorphOptions& options)
{
    const fs::path dict = morph::morph_dict_path(options, fs::absolute(options.case_dir));
    if (!fs::exists(dict))
        return false;
    return io::read_dictionary(dict).find_dict("designVariables") != nullptr;
}

int run_morph_sensitivity(const morph::MorphOptions& options, const fs::path& file,
                          const fs::path& json_path, std::ostream& out)
{
    morph::MorphCase in;
    morph::MorphResult morphed;
    read_case(options, in, morphed);
    const fs::path input = file.is_absolute() ? file : in.mesh_case / file;
    const Points dJdx = read_dJdx(in, input);
    morph_in_memory(options, in, morphed);
    const morph::Decomposition* parts = in.parts(options);
    const Points dJdXs = morph::morph_sensitivity(in, morphed, dJdx, parts);
    const fs::path output = input.parent_path() / "dJdXs";
    io::write_point_vector_field(
        output, in.foam.mesh, dJdXs, input.parent_path().filename().string(),
        "dJ/dXs: dJ/dx of " + input.filename().string() + " through the morph of " +
            morphed.method + ", at its constrained points");
    const parallel::Communicator& comm = parallel::Communicator::world();
    const double largest = comm.max(dJdXs.rowwise().norm().maxCoeff());
    const auto nonzero = comm.sum(std::int64_t((dJdx.rowwise().norm().array() > 0.0).count()));
    log::info() << "dJ/dXs at " << morphed.morph.n_constraints << " constrained points, largest "
                << format_scalar(largest, 6) << "; wrote " << output.string()
                << (parts ? " (and the other processors' dJdXs)" : "");
    if (!json_path.empty() && comm.master())
    {
        const nlohmann::json j = {{"exitStatus", exit_ok},
                                  {"input", input.string()},
                                  {"output", output.string()},
                                  {"method", morphed.method},
                                  {"constrainedPoints", morphed.morph.n_constraints},
                                  {"nonzeroPoints", nonzero},
                                  {"maxMagnitude", largest},
                                  {"morphRefused", morphed.refused}};
        io::write_file_atomic(json_path, j.dump(2) + "\n");
        out << "Wrote " << json_path.string() << "\n";
    }
    return exit_ok;
}

} // namespace meshmorph::app
