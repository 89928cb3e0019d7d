// SPDX-License-Identifier: GPL-3.0-or-later
// morphMesh: its options, the library call morph::morph_case, its JSON and exit status.
#include "meshmorph/app/morph_mesh.h"

#include <ostream>

#include <nlohmann/json.hpp>

#include "meshmorph/app/banner.h"
#include "meshmorph/app/design_commands.h"
#include "meshmorph/app/exit_status.h"
#include "meshmorph/app/options.h"
#include "meshmorph/app/parallel_run.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/morph/deformation_methods.h"
#include "meshmorph/morph/morph_case.h"
#include "meshmorph/parallel/communicator.h"
#include "meshmorph/quality/quality_json.h"

namespace meshmorph::app
{

namespace fs = std::filesystem;

namespace
{

//! `jumpSmoothing auto`'s comparison of a step (null: none, no band or not auto).
nlohmann::json jump_choice_json(const morph::JumpSmoothingChoice& c)
{
    if (!c.compared)
        return nullptr;
    const auto quality = [](const morph::BandQuality& q)
    {
        return nlohmann::json{{"invalidCells", q.invalid_cells},
                              {"maxNonOrthogonality", q.max_non_ortho},
                              {"facesAbove70", q.faces_above_70}};
    };
    return {{"kept", c.kept}, {"smoothed", quality(c.smoothed)}, {"fitted", quality(c.fitted)}};
}

//! {"walls": 95}: the faces the prescription folds, per patch.
nlohmann::json folded_faces_json(const std::vector<morph::PatchFaces>& counts)
{
    nlohmann::json j = nlohmann::json::object();
    for (const morph::PatchFaces& p : counts)
        j[p.patch] = p.faces;
    return j;
}

} // namespace

std::string morph_json(const morph::MorphResult& result, int exit_status)
{
    nlohmann::json j;
    j["exitStatus"] = exit_status;
    j["method"] = result.method;
    j["constraints"] = result.morph.n_constraints;
    j["centres"] = result.morph.report.num_centres;
    j["maxConstraintError"] = result.morph.max_constraint_error;
    j["maxFitResidual"] = result.morph.max_fit_residual;
    j["relativeFitResidual"] = result.morph.relative_fit_residual;
    j["constraintsSnapped"] = result.morph.snapped;
    j["relativeConstraintError"] = result.morph.relative_constraint_error;
    j["maxPrescribedDisplacement"] = result.morph.max_prescribed;
    j["slipPoints"] = result.morph.n_slip;
    j["handlePoints"] = result.constraints.n_handle_points;
    j["conflicts"] = result.constraints.n_conflicts;
    j["nearAgreements"] = result.constraints.n_near_agreements;
    j["conflictRule"] = to_string(result.constraints.conflict_rule);
    j["solver"] = result.morph.report.solver;
    j["conditionEstimate"] = result.morph.report.condition_estimate;
    j["validFraction"] = result.valid_fraction;
    j["maxDisplacement"] = result.max_displacement;
    j["jumpSmoothing"] = morph::to_string(result.constraints.jump_smoothing);
    j["steps"] = nlohmann::json::array();
    for (const morph::StepRecord& s : result.steps)
        j["steps"].push_back({{"from", s.from},
                              {"to", s.to},
                              {"centres", s.centres},
                              {"globalResidual", s.max_global_residual},
                              {"jumpConstraints", s.jump_constraints},
                              {"jumpSmoothedPoints", s.jump_smoothed_points},
                              {"jumpSmoothingChoice", jump_choice_json(s.jump_choice)},
                              {"negativeVolumeCells", s.invalid.negative_volume_cells},
                              {"incorrectlyOrientedFacePyramids", s.invalid.wrong_pyramids},
                              {"untangle",
                               {{"invalidCells", s.untangle.invalid_before},
                                {"pointsMoved", s.untangle.points_moved},
                                {"maxMove", s.untangle.max_move},
                                {"layers", s.untangle.layers},
                                {"stillInvalid", s.untangle.invalid_after},
                                {"belowMargin", s.untangle.below_target_after},
                                {"skippedCells", s.untangle.skipped_cells},
                                {"seconds", s.untangle_seconds}}},
                              {"nonOrthRepair",
                               {{"cells", s.non_ortho.cells},
                                {"pointsMoved", s.non_ortho.points_moved},
                                {"maxMove", s.non_ortho.max_move},
                                {"stillAbove", s.non_ortho.cells_after},
                                {"skippedCells", s.non_ortho.skipped_cells},
                                {"seconds", s.non_ortho.seconds}}},
                              {"accepted", s.accepted},
                              {"fit", s.fit_seconds},
                              {"evaluate", s.evaluate_seconds},
                              {"check", s.check_seconds}});
    j["timings"] = {{"read", result.timings.read},         {"fit", result.timings.fit},
                    {"evaluate", result.timings.evaluate}, {"check", result.timings.check},
                    {"untangle", result.timings.untangle}, {"write", result.timings.write}};
    j["before"] = quality_json(result.before);
    j["after"] = quality_json(result.after);
    if (result.parallel)
        j["parallel"] = parallel::Communicator::world().size();
    j["instance"] = result.instance;
    j["region"] = result.region;
    j["outputInstance"] = result.output_instance;
    j["newFailedChecks"] = failed_checks_json(result.new_failed_checks);
    j["invalidCellsByPatch"] = invalid_cells_json(result.invalid_cells_by_patch);
    j["foldedFaces"] = result.folded.faces;
    j["foldedFacesByPatch"] = folded_faces_json(result.folded.by_patch);
    j["bentSymmetryPlanes"] = nlohmann::json::object();
    for (const NonPlanarSymmetryPlane& b : result.bent_symmetry_planes)
        j["bentSymmetryPlanes"][b.patch] = b.faces;
    j["written"] = result.written;
    j["refused"] = result.refused;
    if (result.refused)
        j["refusal"] = result.refusal;
    return j.dump(2) + "\n";
}

namespace
{

//! morphMesh after its options are parsed; throws on errors (run_guarded reports them).
int morph_mesh_main(const Options& options, const fs::path& json_path, std::ostream& out)
{
    if (options.found("time") && options.found("latestTime"))
        throw UsageError("-time and -latestTime are mutually exclusive");
    if (options.found("overwrite") && options.found("noOverwrite"))
        throw UsageError("-overwrite and -noOverwrite are mutually exclusive");
    morph::MorphOptions morph;
    morph.case_dir = fs::absolute(options.value_or("case", "."));
    if (const std::optional<std::string> d = options.get("dict"))
        morph.dict = *d;
    morph.region = region_option(options);
    if (options.found("latestTime"))
        morph.time = io::TimeSelection::latest_time();
    else if (const std::optional<std::string> t = options.get("time"))
        morph.time = io::TimeSelection::at(*t);
    morph.overwrite = options.found("overwrite");
    if (const std::optional<std::string> m = options.get("method"))
    {
        morph::deformation_method_from_string(*m); // validate early: a usage error
        morph.method = *m;
    }
    morph.scaled_jacobian = !json_path.empty() || vtk_requested(options);
    morph.vtk = vtk_requested(options);
    morph.vtk_file = vtk_file_argument(options);
    morph.force = options.found("force");
    morph.parallel = options.found("parallel");

    print_banner(out, {"morphMesh", options.command_line(), morph.case_dir.string()});
    if (is_design_command(options))
    {
        const int status = run_design_command(options, morph, json_path, out);
        if (status == exit_ok)
            print_end(out);
        return status;
    }
    const morph::MorphResult result = morph::morph_case(morph);
    if (!json_path.empty() && parallel::Communicator::world().master())
    {
        io::write_file_atomic(json_path,
                              morph_json(result, result.refused ? exit_refused : exit_ok));
        out << "Wrote " << json_path.string() << "\n";
    }
    out << "\nTimings [s]: read " << format_seconds(result.timings.read) << ", fit "
        << format_seconds(result.timings.fit) << ", evaluate "
        << format_seconds(result.timings.evaluate) << ", check "
        << format_seconds(result.timings.check) << ", untangle "
        << format_seconds(result.timings.untangle) << ", write "
        << format_seconds(result.timings.write) << "\n";
    if (result.refused)
    {
        // A fold or a bent plane is the prescription's or the conflict rule's: the refusal
        // names the remedy, and a shorter motion or another method would not help.
        const bool remedy_named = result.folded.faces > 0 || !result.bent_symmetry_planes.empty();
        log::error() << result.refusal
                     << (remedy_named
                             ? ". Nothing written (-force writes it anyway)."
                             : ". Nothing written: reduce the motion, change the method or use "
                               "-force.");
        return exit_refused;
    }
    out << (result.after.mesh_ok()
                ? "Mesh OK."
                : "Failed " + std::to_string(result.after.failed_checks) + " mesh checks.")
        << "\n";
    print_end(out);
    return exit_ok;
}

//! morphMesh's options and exit statuses: -help prints them.
Options morph_mesh_options()
{
    const std::vector<OptionSpec> vtk =
        vtk_option_specs("morphMesh", "the displacement and quality");
    return Options(
        "morphMesh",
        "Morphs the polyMesh of an OpenFOAM case with a space deformation (RBF by default,\n"
        "IDW, DM-FFD or FFD) fitted to the boundary and handle prescriptions of\n"
        "system/morphDict, in steps refitted on the moved mesh ('steps auto': one step,\n"
        "halved while a step inverts cells), then checks the result like checkMesh.\n"
        "Without -time or -latestTime it morphs the mesh the case starts from (the first\n"
        "time directory that is not a motion result, i.e. not points without faces, else\n"
        "constant), so a re-run reads the same mesh and writes the same time; name a\n"
        "result with -time or -latestTime to morph it further. Without -overwrite only\n"
        "<that time + deltaT>/polyMesh/points is written (read it with -latestTime); a morph\n"
        "that creates negative-volume cells or wrongly oriented face pyramids is not\n"
        "written unless -force.\n"
        "Conflicting prescriptions on shared points follow the dictionary's 'conflicts' rule\n"
        "(default fixed: such points do not move); handles override boundary prescriptions.",
        {{"case", "DIR", "Case directory (default: the current directory)"},
         {"dict", "FILE", "Alternative morphDict (relative to the case; default system/morphDict)"},
         {"region", "NAME",
          "Morph region NAME (constant/NAME/polyMesh, system/NAME/morphDict, "
          "<time>/NAME/pointDisplacement)"},
         {"time", "TIME", "Morph the mesh at this time (a time name or value, or constant)"},
         {"latestTime", "", "Morph the mesh at the latest time (e.g. an earlier morph's result)"},
         {"overwrite", "", "Replace the points of the mesh instance instead of writing a new time"},
         {"noOverwrite", "", "Write a new time directory (the default)"},
         {"method", "rbf|dmffd|ffd|idw", "Override the dictionary's method"},
         {"json", "FILE",
          "Write constraints, timings and quality as JSON (relative to the working directory)"},
         vtk[0],
         vtk[1],
         {"force", "", "Write even if the morph creates invalid cells"},
         {"parallel", "",
          "Morph the decomposed case (processor*/) under mpirun, one rank per processor "
          "directory"},
         {"variables", "",
          "Set up the morphDict's designVariables once: one field per variable, stored in "
          "constant/designBasis (see tutorials/designVariables)"},
         {"variant", "(a1 a2 ...)",
          "Write the design with these amplitudes (one per design variable) from the set-up: "
          "no fit"},
         {"direction", "(p1 p2 ...)",
          "With -variant: print the largest valid step t along this direction (the design "
          "a + t p checked; nothing written)"},
         {"stepLimit", "T", "With -direction: search steps up to T (default: the bounds)"},
         {"maxNonOrtho", "DEG",
          "With -direction: also keep checkMesh's maximum non-orthogonality at or below DEG "
          "degrees"},
         {"variants", "FILE",
          "Write every row of amplitudes in FILE (a design-of-experiments table) to its own "
          "time directory"},
         {"sensitivity", "FILE",
          "dJ/dx at the points (a pointVectorField, relative to the case) through the "
          "morph: with designVariables dJ/da, printed and written to "
          "postProcessing/morphMesh/dJda; without, dJ/dXs of the morphDict's morph, written "
          "beside FILE as the pointVectorField dJdXs"}},
        {{exit_ok, "morphed mesh written"},
         {exit_input_error, "bad option, dictionary, mesh or surface file; nothing written"},
         {exit_refused, "the morph (or a variant) creates invalid cells, or with morphDict's "
                        "'newCheckFailures refuse' fails a check the mesh passed; nothing "
                        "written (see -force)"},
         {exit_fit_failed, "the deformation could not be fitted; nothing written"},
         {exit_internal_error, "unexpected internal error"}});
}

//! With -json, the report written before the run starts: until the run ends it says it has
//! not, so an interrupted run (SIGINT, SIGKILL) leaves no earlier report saying
//! `written: true`. \return false (after saying why) if the file cannot be written.
bool write_unfinished_report(const fs::path& json_path)
{
    const nlohmann::json unfinished = {
        {"written", false},
        {"exitStatus", nullptr},
        {"error", "the run did not finish (interrupted, killed, or still running)"}};
    try
    {
        io::write_file_atomic(json_path, unfinished.dump(2) + "\n");
    }
    catch (const Error& e)
    {
        log::error() << "-json: " << e.what() << ". Nothing written.";
        return false;
    }
    return true;
}

} // namespace

int run_morph_mesh(int argc, const char* const argv[], std::ostream& out, std::ostream& err)
{
    const log::SinkScope log_to(log::stream_sink(out, err));
    Options options = morph_mesh_options();
    if (const std::optional<int> code = parse_command_line(options, argc, argv, out))
        return *code;
    // -parallel: MPI for the whole run; only the master prints and writes the report.
    std::optional<ParallelRun> run;
    try
    {
        run.emplace(options.found("parallel"));
    }
    catch (const Error& e)
    {
        log::error() << e.what();
        return exit_input_error;
    }
    std::ostringstream discarded;
    const bool master = run->master();
    std::ostream& report_out = master ? out : discarded;
    fs::path json_path; // set as soon as known: a failure replaces any earlier report
    if (const std::optional<std::string> j = options.get("json"))
        json_path = fs::absolute(*j);
    // With -json, a failure writes {written: false, exitStatus, error}.
    const auto report_failure = [&](int status, const std::string& text)
    {
        if (json_path.empty() || !master)
            return;
        try
        {
            const nlohmann::json j = {{"written", false}, {"exitStatus", status}, {"error", text}};
            io::write_file_atomic(json_path, j.dump(2) + "\n");
        }
        catch (const std::exception& e)
        {
            log::error() << "could not write " << json_path.string() << ": " << e.what();
        }
    };
    if (!json_path.empty() && master && !write_unfinished_report(json_path))
        return exit_input_error;
    return run_guarded([&] { return morph_mesh_main(options, json_path, report_out); }, true,
                       report_failure);
}

} // namespace meshmorph::app
