// SPDX-License-Identifier: GPL-3.0-or-later
// -sensitivity without design variables: the morph's reverse pass, written as a point field.
#include "meshmorph/app/morph_sensitivity.h"

#include <nlohmann/json.hpp>
#include <ostream>

#include "meshmorph/app/exit_status.h"
#include "meshmorph/app/morph_session.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/design/design_sensitivity.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/point_field_writer.h"
#include "meshmorph/morph/morph_stages.h"

namespace meshmorph::app
{

namespace fs = std::filesystem;

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
    if (options.parallel)
        throw InvalidInput("-sensitivity of a morph (a morphDict without designVariables) runs "
                           "serially: run it without -parallel (on the reconstructed case)");
    MorphSession session(options);
    const morph::MorphResult& morphed = session.morph();
    if (morphed.refused)
        log::warning() << "the morph itself is refused (" << morphed.refusal
                       << "); dJ/dXs is still that of its field";
    const fs::path input = file.is_absolute() ? file : session.case_dir() / file;
    const Points dJdx = design::read_point_sensitivity(session.mesh(), input);
    const Points dJdXs = session.sensitivity(dJdx);
    const Eigen::VectorXd magnitude = dJdXs.rowwise().norm();
    const Index constrained = Index(morphed.constraints.points.size());
    const fs::path output = input.parent_path() / "dJdXs";
    io::write_point_vector_field(
        output, session.mesh(), dJdXs, input.parent_path().filename().string(),
        "dJ/dXs: dJ/dx of " + input.filename().string() + " through the morph of " +
            morphed.method + ", at its constrained points");
    log::info() << "dJ/dXs at " << constrained << " constrained points, largest "
                << format_scalar(magnitude.maxCoeff(), 6) << "; wrote " << output.string();
    if (!json_path.empty())
    {
        const nlohmann::json j = {
            {"exitStatus", exit_ok},
            {"input", input.string()},
            {"output", output.string()},
            {"method", morphed.method},
            {"constrainedPoints", constrained},
            {"nonzeroPoints", Index((dJdx.rowwise().norm().array() > 0.0).count())},
            {"maxMagnitude", magnitude.maxCoeff()},
            {"morphRefused", morphed.refused}};
        io::write_file_atomic(json_path, j.dump(2) + "\n");
        out << "Wrote " << json_path.string() << "\n";
    }
    return exit_ok;
}

} // namespace meshmorph::app
