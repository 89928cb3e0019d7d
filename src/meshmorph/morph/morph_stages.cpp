// SPDX-License-Identifier: GPL-3.0-or-later
// The stages of a morph of a case: read (dictionary, mesh), constraints, fit and evaluate
// in steps, check after, refuse or write (morph_case.cpp runs them in order).
#include "meshmorph/morph/morph_stages.h"

#include <algorithm>
#include <memory>
#include <sstream>

#include "meshmorph/core/config.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/io/decomposed_case.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/constraints.h"
#include "meshmorph/morph/deformation_dict.h"
#include "meshmorph/morph/deformation_methods.h"
#include "meshmorph/morph/distributed_case.h"
#include "meshmorph/morph/duplicate_points.h"
#include "meshmorph/morph/folded_faces.h"
#include "meshmorph/morph/invalid_cells_location.h"
#include "meshmorph/morph/morph_log.h"
#include "meshmorph/morph/morph_output.h"
#include "meshmorph/morph/new_check_failures.h"
#include "meshmorph/morph/point_displacement_input.h"
#include "meshmorph/morph/surface_projector.h"
#include "meshmorph/parallel/collective.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/quality_summary.h"
#include "meshmorph/quality/symmetry_plane_planarity.h"

namespace meshmorph::morph
{

namespace fs = std::filesystem;

namespace
{

//! The motion in steps (morph_steps.h), with its timings and the constraint error.
SteppedMorph fit_in_steps(const MorphOptions& options, const MorphCase& in, const CompactList& cf,
                          BeforeCheck& before, MorphResult& result, PolyMesh* in_place)
{
    const PolyMesh& mesh = in.foam.mesh;
    const Constraints& c = result.constraints;
    const DeformationSettings& settings = in.settings;
    const Index n_fit = c.n_prescribed_points + c.n_slip_points;
    log::info() << "Method: " << describe(settings, n_fit);
    log::info() << "Steps: "
                << (needs_fit(settings) ? describe(in.step_settings)
                                        : "1 (ffd moves its control points once)");
    const DeformationMaker make = [&](const Points& points)
    { return make_deformation(settings, points, n_fit); };
    const Decomposition* parts = options.parallel ? &in.decomposition : nullptr;
    SteppedMorph stepped = morph_in_steps(
        mesh, cf, c, in.step_settings, make, needs_fit(settings),
        [&before] { return before.invalid(); }, parts, in_place);
    result.steps = stepped.steps;
    for (const StepRecord& s : stepped.steps)
    {
        result.timings.fit += s.fit_seconds;
        result.timings.evaluate += s.evaluate_seconds;
        result.timings.check += s.check_seconds;
        result.timings.untangle += s.untangle_seconds;
        result.timings.untangle += s.non_ortho.seconds;
    }
    result.morph = std::move(stepped.last);
    result.morph.displacement = std::move(stepped.displacement);
    measure_constraint_error(c, mesh.points, result.morph, parts);
    result.max_displacement =
        parallel::Communicator::world().max(max_norm(result.morph.displacement));
    log_fit(result, settings, global_count(in.decomposition, mesh.n_points(), true));
    result.valid_fraction = stepped.valid_fraction;
    return stepped;
}

void warn_if_partly_valid(const SteppedMorph& stepped, const StepSettings& step_settings)
{
    if (stepped.valid_fraction >= 1.0)
        return;
    log::warning() << "the motion is valid up to " << format_scalar(stepped.valid_fraction, 4)
                   << " of itself; beyond, "
                   << (step_settings.steps == 0
                           ? "even a step of 1/" + std::to_string(step_settings.max_steps) +
                                 " of it creates invalid cells"
                           : "a step creates invalid cells (try more steps, or steps auto)");
}

//! Why a morph is refused: invalid cells that were not there before.
std::vector<std::string> refusal_reasons(const QualityReport& before, const QualityReport& after)
{
    std::vector<std::string> reasons;
    if (after.negative_volume_cells > before.negative_volume_cells)
        reasons.push_back(std::to_string(after.negative_volume_cells) + " negative-volume cells (" +
                          std::to_string(before.negative_volume_cells) + " before)");
    if (after.incorrectly_oriented_face_pyramids > before.incorrectly_oriented_face_pyramids)
        reasons.push_back(std::to_string(after.incorrectly_oriented_face_pyramids) +
                          " incorrectly oriented face pyramids (" +
                          std::to_string(before.incorrectly_oriented_face_pyramids) + " before)");
    return reasons;
}

//! Checks the morph makes fail, judged on the master and told to every rank.
std::string judge_new_failures(const MorphCase& in, MorphResult& result)
{
    // The master holds the whole report in a -parallel run: its verdict is every rank's.
    const parallel::Communicator& comm = parallel::Communicator::world();
    std::string refusal;
    if (comm.master())
    {
        result.new_failed_checks = new_failed_checks(result.before, result.after);
        warn_new_check_failures(result.new_failed_checks, "the morphed mesh",
                                in.refuse_new_check_failures);
        if (in.refuse_new_check_failures)
            refusal = new_check_failures_refusal(result.new_failed_checks, "the morphed mesh");
    }
    return comm.broadcast(refusal);
}

//! The symmetryPlane patches of `after` OpenFOAM would refuse that it read in `before`.
std::vector<NonPlanarSymmetryPlane>
bent_symmetry_planes(const std::vector<NonPlanarSymmetryPlane>& before, const PolyMesh& after,
                     const parallel::Communicator& comm)
{
    std::vector<NonPlanarSymmetryPlane> bent = non_planar_symmetry_planes(after, comm);
    std::erase_if(bent,
                  [&](const NonPlanarSymmetryPlane& b)
                  {
                      return std::any_of(before.begin(), before.end(),
                                         [&](const NonPlanarSymmetryPlane& a)
                                         { return a.patch == b.patch; });
                  });
    return bent;
}

//! Why a bent symmetry plane refuses the morph: OpenFOAM's own error, and the remedy.
std::string bent_symmetry_planes_reason(const std::vector<NonPlanarSymmetryPlane>& bent)
{
    std::string names;
    for (const NonPlanarSymmetryPlane& b : bent)
        names += (names.empty() ? "'" : ", '") + b.patch + "' (" + std::to_string(b.faces) +
                 " faces off its average normal beyond OpenFOAM's tolerance)";
    return std::string("the morph bends symmetryPlane ") + names +
           ", and OpenFOAM refuses to read such a mesh (\"Symmetry plane ... is not planar\"): "
           "keep the points it shares with moving patches still (conflicts fixed;) or give the "
           "patch type symmetry";
}

//! The before/after table; then whether the result is refused (true: write nothing).
bool judge(const MorphOptions& options, const MorphCase& in, MorphResult& result)
{
    if (parallel::Communicator::world().master()) // other ranks hold only their part's report
    {
        std::ostringstream summary;
        print_quality_summary(summary, &result.before, &result.after);
        log::info() << "Mesh quality before and after the morph:\n" << summary.str();
    }
    const std::vector<std::string> reasons = refusal_reasons(result.before, result.after);
    const std::string new_failures = judge_new_failures(in, result);
    if (reasons.empty() && new_failures.empty() && result.bent_symmetry_planes.empty())
        return false;
    result.refusal =
        reasons.empty()
            ? new_failures
            : "the morphed mesh has " + reasons.front() +
                  (reasons.size() > 1 ? " and " + reasons.back() : std::string()) +
                  (result.invalid_cells_by_patch.empty()
                       ? std::string()
                       : ", in cells touching " + describe(result.invalid_cells_by_patch));
    if (!reasons.empty() && result.folded.faces > 0) // the cause first
        result.refusal = describe(result.folded) + "; " + result.refusal;
    if (!result.bent_symmetry_planes.empty())
        result.refusal = bent_symmetry_planes_reason(result.bent_symmetry_planes) +
                         (result.refusal.empty() ? "" : "; " + result.refusal);
    if (!options.force)
    {
        result.refused = true; // the caller reports it (morphMesh: exit status 3)
        return true;
    }
    log::warning() << "-force: writing although " << result.refusal;
    return false;
}

} // namespace

fs::path morph_dict_path(const MorphOptions& options, const fs::path& case_dir)
{
    fs::path path =
        options.dict.empty() ? fs::path("system") / options.region / "morphDict" : options.dict;
    return path.is_relative() ? case_dir / path : path;
}

namespace
{

//! -region NAME names a region the case has (constant/NAME/polyMesh): else the error lists
//! those it has, before a missing dictionary of that region could be blamed.
void require_region(const fs::path& case_dir, const std::string& region)
{
    if (region.empty() || region == "region0" ||
        fs::is_directory(case_dir / "constant" / region / "polyMesh") ||
        !io::processor_directories(case_dir).empty()) // decomposed: regions live there
        return;
    std::string regions;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(case_dir / "constant", ec))
        if (fs::is_directory(e.path() / "polyMesh"))
            regions += (regions.empty() ? "" : ", ") + e.path().filename().string();
    throw InvalidInput("-region " + region + ": the case has no such region (no " +
                       (case_dir / "constant" / region / "polyMesh").string() + "); " +
                       (regions.empty()
                            ? std::string("it is a single-region case: leave out -region")
                            : "its regions: " + regions));
}

} // namespace

void read_morph_dict(const MorphOptions& options, MorphCase& in, MorphResult& result)
{
    in.case_dir = fs::absolute(options.case_dir).lexically_normal();
    if (!fs::is_directory(in.case_dir))
        throw IoError("case directory " + in.case_dir.string() + " does not exist");
    require_region(in.case_dir, options.region);
    in.dict_path = morph_dict_path(options, in.case_dir);
    const io::FoamDictionary dict = io::read_dictionary(in.dict_path);
    in.setup = read_morph_setup(dict);
    in.settings = read_deformation_settings(dict, options.method);
    in.step_settings = read_step_settings(dict);
    in.refuse_new_check_failures = read_new_check_failures(dict);
    result.method = to_string(in.settings.method);
}

namespace
{

//! A default run that would read points morphMesh wrote in place (-overwrite) would add to
//! that morph: it refuses and says how to ask for either mesh.
void refuse_to_morph_a_result_by_default(const MorphOptions& options, const io::FoamPolyMesh& foam)
{
    if (options.time.mode != io::TimeSelection::Mode::start || !is_morph_result(foam.points.header))
        return;
    const fs::path orig = foam.points.path.parent_path() /
                          (foam.points.is_compressed ? "points.orig.gz" : "points.orig");
    throw InvalidInput(
        foam.points.path.string() + " holds points morphMesh wrote in place (" +
        foam.points.header.note +
        "), and a run without -time morphs the mesh the case starts from, never a morph's "
        "result. To morph the morphed mesh further, name it: -time " +
        foam.points_instance +
        (fs::exists(orig) ? "; to start again from the original: mv " + orig.string() + " " +
                                foam.points.path.string()
                          : std::string()));
}

} // namespace

void read_morph_mesh(const MorphOptions& options, MorphCase& in, MorphResult& result)
{
    const parallel::Communicator& comm = parallel::Communicator::world();
    in.mesh_case =
        options.parallel ? io::processor_case(in.case_dir, comm, "morphMesh") : in.case_dir;
    io::PolyMeshReadOptions read_options;
    read_options.time = options.time;
    read_options.region = options.region;
    parallel::collective(comm,
                         [&]
                         {
                             in.foam = io::read_poly_mesh(in.mesh_case, read_options);
                             if (options.parallel)
                                 in.decomposition = read_decomposition(in.foam, comm);
                         });
    refuse_to_morph_a_result_by_default(options, in.foam);
    const PolyMesh& mesh = in.foam.mesh;
    result.instance = in.foam.points_instance;
    result.region = options.region;
    result.parallel = options.parallel;
    log::info() << "Read mesh from " << in.foam.points_dir.string()
                << (options.parallel ? " (and the other processors)" : "") << ": "
                << global_count(in.decomposition, mesh.n_points(), true) << " points, "
                << global_count(in.decomposition, mesh.n_cells, false) << " cells, "
                << mesh.patches.size() << " patches";
}

void resolve_constraints(const MorphOptions& options, const MorphCase& in, MorphResult& result,
                         const PointDisplacementInputs* given)
{
    const parallel::Communicator& comm = parallel::Communicator::world();
    const PolyMesh& mesh = in.foam.mesh;
    ConstraintInputs inputs;
    auto projector = std::make_shared<SurfaceProjector>(in.case_dir);
    inputs.project_to_surface = [projector](const std::string& file, const Points& query)
    { return (*projector)(file, query); };
    std::vector<PatchAssignment> assignment;
    parallel::collective(comm,
                         [&] { assignment = assign_patches(mesh, in.setup, options.parallel); });
    inputs.patches = &assignment;
    PointDisplacementInputs displacement;
    if (std::any_of(assignment.begin(), assignment.end(),
                    [](const PatchAssignment& a)
                    { return a.motion == MotionType::point_displacement; }))
    {
        if (given == nullptr)
            displacement = read_point_displacement(in.mesh_case, in.foam, options.region, comm);
        const PointDisplacementInputs& values = given ? *given : displacement;
        inputs.point_displacement = &values.internal;
        inputs.patch_point_displacement = &values.patches;
    }
    if (options.parallel)
        inputs.decomposition = &in.decomposition;
    result.constraints = build_constraints(mesh, in.setup, inputs);
    if (options.parallel)
        set_global_patch_points(mesh, in.decomposition, result.constraints.patches);
    check_duplicate_prescribed_points(mesh, result.constraints, in.foam.points.path.string());
}

std::string morph_output_instance(const MorphOptions& options, const MorphCase& in)
{
    if (options.overwrite)
        return in.foam.points_instance;
    std::vector<io::TimeDir> times = io::list_times(in.mesh_case);
    // A default run writes where the first one did: the times after its start are results.
    if (options.time.mode == io::TimeSelection::Mode::start)
        times = io::start_times(in.mesh_case, times, in.foam.region);
    return io::next_time_name(times, in.foam.time, io::read_time_settings(in.case_dir));
}

void check_output_options(const MorphOptions& options)
{
    if (options.parallel && options.vtk)
        throw InvalidInput("-vtk is not available with -parallel yet (reconstructPar, then "
                           "checkMeshQuality -vtk)");
#if !MESHMORPH_WITH_VTK
    if (options.vtk)
        throw InvalidInput("-vtk: this build has no VTK support (MESHMORPH_WITH_VTK=OFF)");
#endif
}

void morph_resolved(const MorphOptions& options, const MorphCase& in, const CompactList& cf,
                    BeforeCheck& before, MorphResult& result, std::optional<PolyMesh>& moved,
                    PolyMesh* spent)
{
    const parallel::Communicator& comm = options.parallel && in.decomposition.comm != nullptr
                                             ? *in.decomposition.comm
                                             : parallel::Communicator::world();
    // Said before the steps: halving may still find valid cells around a folded face (the
    // cell turns over with it), so the morph goes on as asked; a refusal names the fold first.
    result.folded = faces_folded_by_prescription(in.foam.mesh, result.constraints, comm);
    if (result.folded.faces > 0)
        log::warning() << describe(result.folded);
    // Before the steps: with `spent` they move in.foam.mesh's own points.
    const std::vector<NonPlanarSymmetryPlane> bent_before =
        non_planar_symmetry_planes(in.foam.mesh, comm);
    SteppedMorph stepped = fit_in_steps(options, in, cf, before, result, spent);
    result.before = before.take_report();
    result.timings.check += before.waited_seconds();
    const Stopwatch stage;
    warn_if_partly_valid(stepped, in.step_settings);
    if (!moved && spent != nullptr)
        moved.emplace(std::move(*spent)); // its points are replaced below: nothing is copied
    else if (!moved)
        moved.emplace(in.foam.mesh);
    moved->points = std::move(stepped.points); // exactly the points stepped.geometry is of
    CheckMeshSettings check_settings;
    check_settings.scaled_jacobian = options.scaled_jacobian;
    check_settings.cell_fields = options.vtk;                     // the VTK file shows them
    check_settings.unchanged_topology = &result.before;           // only the points moved
    check_settings.face_pyramid_errors = &stepped.pyramid_errors; // counted after the last step
    result.after = check_morph_mesh(*moved, cf, stepped.geometry, check_settings, in.decomposition);
    if (!refusal_reasons(result.before, result.after).empty()) // the counts are every rank's
        result.invalid_cells_by_patch = invalid_cells_by_patch(*moved, cf, stepped.geometry, comm);
    result.bent_symmetry_planes = bent_symmetry_planes(bent_before, *moved, comm);
    result.timings.check += stage.seconds();
    judge(options, in, result);
}

void write_morph_result(const MorphOptions& options, const MorphCase& in, const PolyMesh& moved,
                        MorphResult& result)
{
    const Stopwatch stage;
    parallel::collective(
        parallel::Communicator::world(),
        [&]
        {
            if (!options.overwrite)
                warn_if_replacing(in.mesh_case, result.output_instance, in.foam.region);
            if (!options.parallel)
                warn_if_decomposed(in.case_dir);
            result.points_file = write_morphed_points(options, moved.points, in.foam, in.mesh_case,
                                                      result.output_instance);
        });
    result.written = true;
    if (options.vtk)
        write_vtk(in.case_dir, options, moved, result);
    result.timings.write = stage.seconds();
    log::info() << "Wrote " << result.points_file.string() << " in "
                << format_seconds(result.timings.write) << " s";
    if (!result.vtk_file.empty())
        log::info() << "Wrote " << result.vtk_file.string()
                    << " (point data: displacement; cell data: nonOrthogonality, skewness, "
                       "aspectRatio)";
}

} // namespace meshmorph::morph
