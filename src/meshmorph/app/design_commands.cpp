// SPDX-License-Identifier: GPL-3.0-or-later
// -variables, -variant, -variants, -sensitivity: the design/ module's calls with morphMesh's
// log lines and JSON.
#include "meshmorph/app/design_commands.h"

#include <cmath>
#include <limits>
#include <ostream>

#include <nlohmann/json.hpp>

#include "meshmorph/app/exit_status.h"
#include "meshmorph/app/morph_sensitivity.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/design/amplitude_table.h"
#include "meshmorph/design/design_sensitivity.h"
#include "meshmorph/design/design_setup.h"
#include "meshmorph/design/design_variant.h"
#include "meshmorph/design/valid_step.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/parallel/communicator.h"
#include "meshmorph/quality/quality_json.h"
#include "meshmorph/quality/quality_summary.h"

namespace meshmorph::app
{

namespace fs = std::filesystem;

namespace
{

constexpr const char* commands[] = {"variables", "variant", "variants", "sensitivity"};

void check_design_options(const Options& options)
{
    int n = 0;
    for (const char* c : commands)
        n += options.found(c) ? 1 : 0;
    if (n > 1)
        throw UsageError("-variables, -variant, -variants and -sensitivity are mutually "
                         "exclusive (one design command per run)");
    for (const char* other : {"vtk", "vtkFile"})
        if (options.found(other))
            throw UsageError(std::string("-") + other +
                             " is not available with the design commands yet");
    if (options.found("method") && !options.found("variables"))
        throw UsageError("-method goes with -variables (a variant uses its set-up's method)");
    if (options.found("direction") && !options.found("variant"))
        throw UsageError("-direction goes with -variant (the design the step search starts "
                         "from)");
    for (const char* o : {"stepLimit", "maxNonOrtho"})
        if (options.found(o) && !options.found("direction"))
            throw UsageError(std::string("-") + o +
                             " goes with -direction (it limits the step search)");
}

//! Write the report `j` to `path` (none if empty; the master only); say so unless `quiet`.
void write_json(const fs::path& path, const nlohmann::json& j, std::ostream& out,
                bool quiet = false)
{
    if (path.empty() || !parallel::Communicator::world().master())
        return;
    io::write_file_atomic(path, j.dump(2) + "\n");
    if (!quiet)
        out << "Wrote " << path.string() << "\n";
}

int run_setup(const morph::MorphOptions& morph, const fs::path& json_path, std::ostream& out)
{
    const design::DesignSetupResult r = design::setup_design(morph);
    write_json(json_path, setup_json(r), out);
    out << "\nDesign set-up written: " << r.names.size() << " variables in "
        << format_seconds(r.seconds) << " s.\n";
    return exit_ok;
}

//! The log of one variant (`row`: "row 3: " for -variants, else ""); true when refused.
bool report_variant(const design::DesignStudy& study, const design::VariantResult& r,
                    std::ostream& out, const std::string& row = "")
{
    log::info() << "Variant: max displacement " << format_scalar(r.max_displacement, 4)
                << ", constraint error " << format_scalar(r.relative_constraint_error, 3)
                << " of the largest prescribed displacement";
    std::ostringstream summary;
    print_quality_summary(summary, nullptr, &r.after);
    log::info() << "Mesh quality of the variant:\n" << summary.str();
    study.warn_new_check_failures(r);
    if (r.refused)
    {
        log::error() << row << r.refusal << ". Nothing written"
                     << (r.back_off.empty() ? std::string(".") : ": back off " + r.back_off + ".");
        return true;
    }
    log::info() << "Wrote " << r.points_file.string();
    out << (r.after.mesh_ok() ? "Mesh OK."
                              : "Failed " + std::to_string(r.after.failed_checks) + " mesh checks.")
        << "\n";
    return false;
}

std::string first_instance(const design::DesignStudy& study, const morph::MorphOptions& morph)
{
    const io::FoamPolyMesh& foam = study.design_case().foam;
    return morph.overwrite ? foam.points_instance : study.next_instance(foam.time);
}

int run_variant(const morph::MorphOptions& morph, const std::string& text,
                const fs::path& json_path, std::ostream& out)
{
    const std::vector<double> a = design::parse_amplitudes(text);
    design::DesignStudy study(morph);
    const design::VariantResult r = study.apply(a, first_instance(study, morph));
    const bool refused = report_variant(study, r, out);
    const int status = refused ? exit_refused : exit_ok;
    nlohmann::json j = variant_json(study, r);
    j["exitStatus"] = status;
    write_json(json_path, j, out);
    out << "\nTimings [s]: read " << format_seconds(study.read_seconds()) << ", combine "
        << format_seconds(r.combine_seconds) << ", check " << format_seconds(r.check_seconds)
        << ", write " << format_seconds(r.write_seconds) << "\n";
    return status;
}

//! A step for the JSON: null when unbounded (JSON has no infinity).
nlohmann::json step_json(double t)
{
    return std::isfinite(t) ? nlohmann::json(t) : nlohmann::json(nullptr);
}

std::string limit_text(const design::ValidStep& r)
{
    if (r.limited_by == "inversion")
        return "a cell inverts by " + format_scalar(r.invalid_above, 6);
    if (r.limited_by == "bounds")
        return r.bound_variable + " reaches its bound";
    if (r.limited_by == "limit")
        return "the step limit";
    if (r.limited_by == "nonOrthogonality")
        return "the maximum non-orthogonality passes the limit by " +
               format_scalar(r.invalid_above, 6);
    return "nothing inverts along the direction, and no variable along it is bounded";
}

//! -variant A -direction P: the largest valid step along P from A; writes no mesh.
int run_step_search(const morph::MorphOptions& morph, const Options& options,
                    const fs::path& json_path, std::ostream& out)
{
    const std::vector<double> a = design::parse_amplitudes(*options.get("variant"));
    const std::vector<double> p = design::parse_amplitudes(*options.get("direction"));
    const double limit =
        options.get_scalar("stepLimit").value_or(std::numeric_limits<double>::infinity());
    design::DesignStudy study(morph);
    log::info() << "Step search along -direction from -variant (" << study.names().size()
                << " variables)";
    const design::ValidStep r = design::largest_valid_step(
        study, a, p, limit, options.get_scalar("maxNonOrtho").value_or(90.0));
    log::info() << "Estimated first inversion (cubic pyramid volumes): "
                << (std::isfinite(r.estimate) ? format_scalar(r.estimate, 6) : "none");
    nlohmann::json j = valid_step_json(study, a, p, r);
    j["exitStatus"] = exit_ok;
    write_json(json_path, j, out);
    out << "\nLargest valid step: " << (std::isfinite(r.step) ? format_scalar(r.step, 6) : "inf")
        << " (" << limit_text(r) << "; " << r.checks << " checks, " << format_seconds(r.seconds)
        << " s). Nothing written.\n";
    return exit_ok;
}

int run_variants(const morph::MorphOptions& morph, const fs::path& table, const fs::path& json_path,
                 std::ostream& out)
{
    if (morph.overwrite)
        throw UsageError("-variants writes each row to its own time directory: -overwrite "
                         "would keep only the last");
    design::DesignStudy study(morph);
    const std::vector<std::vector<double>> rows =
        design::read_amplitude_table(table, study.names());
    for (std::size_t k = 0; k < rows.size(); ++k) // every row checked before any is written
        try
        {
            study.check_amplitudes(rows[k]);
        }
        catch (const InvalidInput& e)
        {
            throw InvalidInput(table.string() + ": row " + std::to_string(k + 1) + " (" +
                               "counting data rows from 1): " + e.what());
        }
    nlohmann::json list = nlohmann::json::array();
    std::string instance = study.design_case().foam.time;
    int refused = 0;
    for (std::size_t k = 0; k < rows.size(); ++k)
    {
        instance = study.next_instance(instance);
        log::info() << "Row " << k + 1 << " of " << rows.size() << " -> " << instance;
        const design::VariantResult r = study.apply(rows[k], instance);
        refused += report_variant(study, r, out, "row " + std::to_string(k + 1) + ": ") ? 1 : 0;
        nlohmann::json j = variant_json(study, r);
        j["row"] = k + 1;
        list.push_back(j);
        // Each row is on record as soon as it is written: an interrupted run's report says
        // which rows exist (exitStatus null and finished false until the last).
        write_json(json_path, {{"exitStatus", nullptr}, {"finished", false}, {"rows", list}}, out,
                   true);
    }
    const int status = refused > 0 ? exit_refused : exit_ok;
    write_json(json_path, {{"exitStatus", status}, {"finished", true}, {"rows", list}}, out);
    out << "\n"
        << rows.size() - std::size_t(refused) << " of " << rows.size() << " variants written"
        << (refused > 0 ? " (the others refused)" : "") << ".\n";
    return status;
}

int run_sensitivity(const morph::MorphOptions& morph, const fs::path& file,
                    const fs::path& json_path, std::ostream& out)
{
    if (!declares_design_variables(morph))
        return run_morph_sensitivity(morph, file, json_path, out);
    design::DesignStudy study(morph);
    const design::SensitivityResult r = design::design_sensitivity(study, file);
    nlohmann::json gradient;
    for (std::size_t j = 0; j < r.names.size(); ++j)
        gradient[r.names[j]] = r.gradient[j];
    write_json(json_path,
               {{"exitStatus", exit_ok},
                {"setupReused", true},
                {"input", r.input.string()},
                {"output", r.output.string()},
                {"names", r.names},
                {"dJda", gradient},
                {"nonzeroPoints", r.nonzero_points}},
               out);
    return exit_ok;
}

} // namespace

nlohmann::json setup_json(const design::DesignSetupResult& r)
{
    nlohmann::json variables = nlohmann::json::array();
    for (std::size_t j = 0; j < r.names.size(); ++j)
        variables.push_back({{"name", r.names[j]},
                             {"movesPoints", bool(r.moves[j])},
                             {"maxConstraintError", r.fits[j].max_constraint_error},
                             {"relativeConstraintError", r.fits[j].relative_constraint_error},
                             {"centres", r.fits[j].centres},
                             {"seconds", r.fits[j].seconds}});
    return {{"exitStatus", exit_ok},
            {"setupFile", r.basis_file.string()},
            {"method", r.method},
            {"points", r.n_points},
            {"constrainedPoints", r.n_constrained},
            {"storage", r.storage},
            {"storageReason", r.storage_reason},
            {"variables", variables},
            {"bytes", r.bytes},
            {"seconds", r.seconds},
            {"before", quality_json(r.before)}};
}

nlohmann::json invalid_cells_json(const std::vector<morph::PatchCells>& counts)
{
    nlohmann::json j = nlohmann::json::object();
    for (const morph::PatchCells& p : counts)
        j[p.patch] = p.cells;
    return j;
}

nlohmann::json variant_json(const design::DesignStudy& study, const design::VariantResult& r)
{
    nlohmann::json amplitudes;
    for (std::size_t j = 0; j < r.amplitudes.size(); ++j)
        amplitudes[study.names()[j]] = r.amplitudes[j];
    nlohmann::json j = {
        {"setupReused", true},
        {"setupFile", study.basis_file().string()},
        {"amplitudes", amplitudes},
        {"valid", !r.refused},
        {"written", r.written},
        {"outputInstance", r.output_instance},
        {"path", r.points_file.string()},
        {"maxPrescribedDisplacement", r.max_prescribed},
        {"maxConstraintError", r.max_constraint_error},
        {"relativeConstraintError", r.relative_constraint_error},
        {"maxDisplacement", r.max_displacement},
        {"timings",
         {{"combine", r.combine_seconds}, {"check", r.check_seconds}, {"write", r.write_seconds}}},
        {"after", quality_json(r.after)},
        {"newFailedChecks", failed_checks_json(r.new_failed_checks)},
        {"invalidCellsByPatch", invalid_cells_json(r.invalid_cells_by_patch)}};
    if (!r.repair.skipped.empty())
        j["untangle"] = {{"skipped", r.repair.skipped}};
    if (r.repair.tried)
        j["untangle"] = {{"invalidBefore", r.repair.invalid_before},
                         {"invalidAfter", r.repair.invalid_after},
                         {"pointsMoved", r.repair.points_moved},
                         {"maxMove", r.repair.max_move},
                         {"seconds", r.repair.seconds}};
    if (r.refused)
    {
        j["refusal"] = r.refusal;
        j["backOff"] = r.back_off;
    }
    return j;
}

nlohmann::json valid_step_json(const design::DesignStudy& study, const std::vector<double>& a,
                               const std::vector<double>& direction, const design::ValidStep& r)
{
    nlohmann::json amplitudes, along;
    for (std::size_t j = 0; j < a.size(); ++j)
    {
        amplitudes[study.names()[j]] = a[j];
        along[study.names()[j]] = direction[j];
    }
    return {{"setupReused", true},
            {"setupFile", study.basis_file().string()},
            {"written", false},
            {"amplitudes", amplitudes},
            {"direction", along},
            {"step", step_json(r.step)},
            {"invalidAbove", step_json(r.invalid_above)},
            {"estimate", step_json(r.estimate)},
            {"limitedBy", r.limited_by},
            {"boundVariable", r.bound_variable},
            {"maxNonOrthogonality", r.max_non_orthogonality}, // NaN (null): not asked for
            {"checks", r.checks},
            {"seconds", r.seconds}};
}

bool is_design_command(const Options& options)
{
    for (const char* c : commands)
        if (options.found(c))
            return true;
    // The step search's options alone: check_design_options says which command they need.
    for (const char* o : {"direction", "stepLimit", "maxNonOrtho"})
        if (options.found(o))
            return true;
    return false;
}

int run_design_command(const Options& options, const morph::MorphOptions& morph,
                       const fs::path& json_path, std::ostream& out)
{
    check_design_options(options);
    if (options.found("variables"))
        return run_setup(morph, json_path, out);
    if (options.found("direction"))
        return run_step_search(morph, options, json_path, out);
    if (const std::optional<std::string> v = options.get("variant"))
        return run_variant(morph, *v, json_path, out);
    if (const std::optional<std::string> t = options.get("variants"))
        return run_variants(morph, fs::absolute(*t), json_path, out);
    return run_sensitivity(morph, *options.get("sensitivity"), json_path, out);
}

} // namespace meshmorph::app
