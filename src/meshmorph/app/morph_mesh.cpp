// SPDX-License-Identifier: GPL-3.0-or-later
// The morph pipeline: constraints -> fitted space deformation -> displaced mesh points.
#include "meshmorph/app/morph_mesh.h"

#include "meshmorph/app/exit_status.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>

#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "meshmorph/app/banner.h"
#include "meshmorph/app/decomposed_case.h"
#include "meshmorph/app/deformation_factory.h"
#include "meshmorph/app/options.h"
#include "meshmorph/core/config.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/progress.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/core/triangle_surface.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/point_field.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/surface_io.h"
#include "meshmorph/io/write_poly_mesh.h"
#include "meshmorph/morph/duplicate_points.h"
#include "meshmorph/parallel/collective.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/parallel_report.h"
#include "meshmorph/quality/quality_json.h"
#if MESHMORPH_WITH_VTK
#include "meshmorph/io/vtk_writer.h"
#endif

namespace meshmorph::app
{

namespace fs = std::filesystem;

namespace
{

std::string fmt(double v, int precision = 3)
{
    std::ostringstream o;
    o.precision(precision);
    o << v;
    return o.str();
}

//! Reads target surfaces once per file (paths relative to the case) and projects points
//! onto them (exact closest point, AABB tree).
class SurfaceProjector
{
public:
    explicit SurfaceProjector(fs::path case_dir) : case_dir_(std::move(case_dir)) {}
    Points operator()(const std::string& file, const Points& query)
    {
        auto it = trees_.find(file);
        if (it == trees_.end())
        {
            fs::path path = file;
            if (path.is_relative())
                path = case_dir_ / path;
            TriangleSurface surface = io::read_surface(path);
            log::info() << "Read target surface " << path.string() << ": " << surface.n_triangles()
                        << " triangles";
            it = trees_.emplace(file, std::make_shared<SurfaceTree>(std::move(surface))).first;
        }
        return it->second->closest_points(query);
    }

private:
    fs::path case_dir_;
    std::map<std::string, std::shared_ptr<SurfaceTree>> trees_;
};

//! -overwrite replaces the mesh's own points: the first time, they are kept beside them as
//! points.orig (points.orig.gz), byte for byte, so a user can always go back; later
//! overwrites say that they compound the motion. Returns the file it created (empty: none),
//! which a failed write removes again.
fs::path keep_original_points(const fs::path& points_file)
{
    const bool gz = points_file.extension() == ".gz";
    const fs::path orig = points_file.parent_path() / (gz ? "points.orig.gz" : "points.orig");
    const auto read_bytes = [](const fs::path& path)
    {
        std::ifstream in(path, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        if (!in.good() && !in.eof())
            throw IoError("cannot read " + path.string());
        return bytes.str();
    };
    const std::string bytes = read_bytes(points_file);
    if (fs::exists(orig))
    {
        // A run killed between the two writes leaves an orig equal to the points: nothing
        // was morphed, and the orig is already what it should be.
        if (read_bytes(orig) != bytes)
            log::warning() << "-overwrite: " << points_file.string() << " was morphed before ("
                           << orig.filename().string()
                           << " exists): this morph adds to that one. The original points are in "
                           << orig.string();
        return {};
    }
    io::write_file_atomic(orig, bytes);
    log::info() << "-overwrite: the original points are kept in " << orig.string()
                << " (to undo: mv " << orig.filename().string() << " "
                << points_file.filename().string() << ")";
    return orig;
}

//! The morphed points, and with -overwrite the original kept first; a failure removes what
//! this run created, so a failed write leaves the case as it was.
fs::path write_morphed_points(const MorphOptions& options, const Points& points,
                              const io::FoamPolyMesh& foam, const fs::path& mesh_case,
                              const std::string& instance)
{
    const fs::path orig = options.overwrite ? keep_original_points(foam.points.path) : fs::path();
    try
    {
        return io::write_points(points, foam.points, mesh_case, instance, foam.region);
    }
    catch (const Error&)
    {
        std::error_code ignored;
        if (!orig.empty())
            fs::remove(orig, ignored);
        throw;
    }
}

//! A mesh that already fails checks (open cells, zero-area faces, ...) is morphed (only new
//! invalid cells refuse a morph), but the user hears that the result inherits the damage.
void warn_if_broken(const QualityReport& before, const fs::path& mesh_dir)
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

//! Without -overwrite a re-run replaces the points an earlier run wrote: say so.
void warn_if_replacing(const fs::path& case_dir, const std::string& instance,
                       const std::string& region)
{
    const fs::path dir = case_dir / instance / region / "polyMesh";
    for (const char* name : {"points", "points.gz"})
        if (fs::exists(dir / name))
            log::warning() << "replacing " << (dir / name).string()
                           << " (written by an earlier run; use -overwrite or another -time to "
                              "keep it)";
}

//! This rank's point labels in the undecomposed mesh (decomposePar's pointProcAddressing).
morph::Decomposition read_decomposition(const io::FoamPolyMesh& foam,
                                        const parallel::Communicator& comm)
{
    return morph::make_decomposition(foam.mesh, read_point_addressing(foam), comm);
}

//! A count over the whole mesh: cells are split between the ranks; points are shared, and
//! the undecomposed mesh has (largest label + 1) of them.
Index global_count(const morph::Decomposition& d, Index local, bool points)
{
    if (!d.is_distributed())
        return local;
    if (!points)
        return Index(d.comm->sum(std::int64_t(local)));
    return global_point_count(d.global_point, *d.comm);
}

//! The patches' point counts over every rank (a shared point once), for the set-up lines.
void set_global_patch_points(const PolyMesh& mesh, const morph::Decomposition& d,
                             std::vector<morph::PatchAssignment>& patches)
{
    std::vector<std::array<Index, 2>> mine; // (patch, global label)
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        for (Index point : patch_points(mesh, mesh.patches[p]))
            mine.push_back({Index(p), d.global_point[std::size_t(point)]});
    std::vector<Index> counts(patches.size(), 0);
    const auto gathered = d.comm->gather_values(mine); // on the master only
    if (d.comm->master())
    {
        std::vector<std::array<Index, 2>> all;
        for (const auto& rank : gathered)
            all.insert(all.end(), rank.begin(), rank.end());
        std::sort(all.begin(), all.end());
        all.erase(std::unique(all.begin(), all.end()), all.end());
        for (const auto& [patch, label] : all)
            if (std::size_t(patch) < counts.size())
                ++counts[std::size_t(patch)];
    }
    for (std::size_t p = 0; p < patches.size(); ++p)
        patches[p].n_points = counts[p];
}

//! The check of a -parallel run (as checkMeshQuality -parallel's): every rank checks its
//! part with the processor faces coupled; the master holds the report of the whole mesh.
//! The two counts a morph is judged by are summed on every rank, so that all refuse alike.
QualityReport distributed_check(const PolyMesh& mesh, const CompactList& cf,
                                const MeshGeometry& geometry, const CheckMeshSettings& settings,
                                const morph::Decomposition& d)
{
    const parallel::Communicator& comm = *d.comm;
    const ProcessorFaces processors = exchange_processor_faces(mesh, geometry, comm);
    const QualityReport local = check_mesh(mesh, cf, geometry, settings, &processors);
    QualityReport r =
        reduce_report(local, mesh, settings, processors, global_point_count(d.global_point, comm));
    r.negative_volume_cells = Index(comm.sum(std::int64_t(local.negative_volume_cells)));
    r.incorrectly_oriented_face_pyramids =
        Index(comm.sum(std::int64_t(local.incorrectly_oriented_face_pyramids)));
    return r;
}

//! check_mesh, or distributed_check in a -parallel run.
QualityReport check_morph_mesh(const PolyMesh& mesh, const CompactList& cf,
                               const MeshGeometry& geometry, const CheckMeshSettings& settings,
                               const morph::Decomposition& d)
{
    return d.is_distributed() ? distributed_check(mesh, cf, geometry, settings, d)
                              : check_mesh(mesh, cf, geometry, settings);
}

double max_norm(const Points& d)
{
    return d.rows() > 0 ? d.rowwise().norm().maxCoeff() : 0.0;
}

//! A decomposed case keeps its own copy of the mesh in every processor directory: a serial
//! morph changes only the undecomposed mesh, and a parallel run would use the old one.
void warn_if_decomposed(const fs::path& case_dir)
{
    const std::vector<std::string> dirs = processor_directories(case_dir);
    if (dirs.empty())
        return;
    log::warning() << "the case is decomposed (" << dirs.front()
                   << (dirs.size() > 1 ? " ... " + dirs.back() : std::string())
                   << "): this morph changes only the undecomposed mesh; the processor "
                      "directories still hold the old mesh (decompose again, e.g. "
                      "decomposePar -force, before a parallel run)";
}

//! The set-up, as the user should see it: per patch its motion and why, the constraint
//! counts, conflicts and near agreements.
void log_setup(const morph::Constraints& c)
{
    for (const morph::PatchAssignment& a : c.patches)
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

//! The pointDisplacement values a type pointDisplacement needs.
struct PointDisplacementInputs
{
    Points internal;
    std::vector<std::optional<Points>> patches;
};

//! <time>[/<region>]/pointDisplacement of the time read (0/ when the mesh came from
//! constant/). Patches of type pointDisplacement take their boundaryField values (fixedValue /
//! calculated), else the internalField at their points; other patches' entries are not used,
//! so their disagreements do not matter here.
PointDisplacementInputs read_point_displacement(const fs::path& mesh_case,
                                                const io::FoamPolyMesh& foam,
                                                const std::string& region,
                                                const parallel::Communicator& comm)
{
    const std::string time = foam.time == "constant" ? "0" : foam.time;
    io::PointVectorField field;
    parallel::collective(comm,
                         [&]
                         {
                             field = io::read_point_vector_field(
                                 mesh_case / time / region / "pointDisplacement", foam.mesh);
                         });
    PointDisplacementInputs out{field.internal, {}};
    for (const io::PointPatchField& pf : field.patches)
        out.patches.push_back(pf.value);
    log::info() << "Read " << field.path.string();
    return out;
}

//! The fit and the field, as the user should see them: centres, residuals, the largest
//! displacement against the largest prescribed one, the constraint error.
void log_fit(const MorphResult& result, const DeformationSettings& settings, Index n_points)
{
    const FitReport& r = result.morph.report;
    log::info() << "Fitted " << result.morph.n_constraints << " constraints with " << r.num_centres
                << (settings.method == DeformationMethod::rbf ? " centres" : " control points")
                << (r.solver.empty() ? std::string() : " (" + r.solver + ")")
                << (r.condition_estimate > 0 ? ", condition ~ " + fmt(r.condition_estimate) : "")
                << " in " << format_seconds(result.timings.fit) << " s";
    log::info() << "Evaluated " << n_points << " points in "
                << format_seconds(result.timings.evaluate) << " s; max displacement "
                << fmt(result.max_displacement);
    if (r.method.ends_with("+idw"))
        log::info() << "Global RBF residual " << fmt(r.max_residual) << " ("
                    << fmt(r.max_residual / std::max(r.max_displacement, 1e-300))
                    << " relative), taken up by the local IDW correction";
    log::info() << "Largest displacement " << fmt(result.max_displacement)
                << " (largest prescribed " << fmt(result.morph.max_prescribed) << ")";
    if (result.max_displacement > 1.01 * result.morph.max_prescribed &&
        result.morph.max_prescribed > 0.0)
        log::warning() << "points away from the constraints move up to "
                       << fmt(result.max_displacement / result.morph.max_prescribed)
                       << " times the largest prescribed displacement (the global RBF "
                          "overshoots): method idw never exceeds it; rbf { kernel biharmonic; } "
                          "overshoots less than the triharmonic kernel";
    log::info() << "Max constraint error " << fmt(result.morph.max_constraint_error) << " ("
                << fmt(result.morph.relative_constraint_error)
                << " of the largest prescribed displacement " << fmt(result.morph.max_prescribed)
                << ")";
    if (is_exact(settings) && result.morph.relative_constraint_error > 1e-9)
        log::warning() << "the constrained points miss their prescriptions by up to "
                       << fmt(result.morph.relative_constraint_error)
                       << " (relative): report this case, the field should interpolate them";
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

//! -vtk: the morphed mesh with the displacement and the quality fields.
void write_vtk(const fs::path& case_dir, const MorphOptions& options, const PolyMesh& moved,
               MorphResult& result)
{
#if MESHMORPH_WITH_VTK
    result.vtk_file =
        options.vtk_file.empty()
            ? default_vtk_file(case_dir, "morphMesh", options.region, result.output_instance)
            : options.vtk_file;
    { // a read-only or full file system is an input error naming the directory
        std::error_code ec;
        fs::create_directories(result.vtk_file.parent_path(), ec);
        if (ec)
            throw IoError("Cannot create directory " + result.vtk_file.parent_path().string() +
                          ": " + ec.message());
    }
    std::vector<io::VtkField> point_data;
    point_data.emplace_back("displacement", result.morph.displacement);
    std::vector<io::VtkField> cell_data;
    if (result.after.cell_non_orthogonality.size() == moved.n_cells)
        cell_data.emplace_back("nonOrthogonality", result.after.cell_non_orthogonality);
    if (result.after.cell_skewness.size() == moved.n_cells)
        cell_data.emplace_back("skewness", result.after.cell_skewness);
    if (result.after.cell_aspect_ratio.size() == moved.n_cells)
        cell_data.emplace_back("aspectRatio", result.after.cell_aspect_ratio);
    io::write_vtu(result.vtk_file, moved, point_data, cell_data);
#else
    (void)case_dir, (void)options, (void)moved, (void)result;
#endif
}

} // namespace

MorphResult morph_case(const MorphOptions& options)
{
    MorphResult result;
    const fs::path case_dir = fs::absolute(options.case_dir);
    if (!fs::is_directory(case_dir))
        throw IoError("case directory " + case_dir.string() + " does not exist");
    fs::path dict_path =
        options.dict.empty() ? fs::path("system") / options.region / "morphDict" : options.dict;
    if (dict_path.is_relative())
        dict_path = case_dir / dict_path;

    // Everything that can fail on user input happens before anything is written.
    Stopwatch stage;
    const io::FoamDictionary dict = io::read_dictionary(dict_path);
    morph::MorphSetup setup = morph::read_morph_setup(dict);
    const DeformationSettings settings = read_deformation_settings(dict, options.method);
    const morph::StepSettings step_settings = morph::read_step_settings(dict);
    result.method = to_string(settings.method);

    const parallel::Communicator& comm = parallel::Communicator::world();
    const fs::path mesh_case =
        options.parallel ? processor_case(case_dir, comm, "morphMesh") : case_dir;
    io::PolyMeshReadOptions read_options;
    read_options.time = options.time;
    read_options.region = options.region;
    io::FoamPolyMesh foam;
    morph::Decomposition decomposition;
    parallel::collective(comm,
                         [&]
                         {
                             foam = io::read_poly_mesh(mesh_case, read_options);
                             if (options.parallel)
                                 decomposition = read_decomposition(foam, comm);
                         });
    const PolyMesh& mesh = foam.mesh;
    result.instance = foam.points_instance;
    result.region = options.region;
    result.parallel = options.parallel;
    log::info() << "Read mesh from " << foam.points_dir.string()
                << (options.parallel ? " (and the other processors)" : "") << ": "
                << global_count(decomposition, mesh.n_points(), true) << " points, "
                << global_count(decomposition, mesh.n_cells, false) << " cells, "
                << mesh.patches.size() << " patches";

    morph::ConstraintInputs inputs;
    auto projector = std::make_shared<SurfaceProjector>(case_dir);
    inputs.project_to_surface = [projector](const std::string& file, const Points& query)
    { return (*projector)(file, query); };
    std::vector<morph::PatchAssignment> assignment;
    parallel::collective(comm, [&]
                         { assignment = morph::assign_patches(mesh, setup, options.parallel); });
    inputs.patches = &assignment;
    PointDisplacementInputs displacement;
    if (std::any_of(assignment.begin(), assignment.end(),
                    [](const morph::PatchAssignment& a)
                    { return a.motion == morph::MotionType::point_displacement; }))
    {
        displacement = read_point_displacement(mesh_case, foam, options.region, comm);
        inputs.point_displacement = &displacement.internal;
        inputs.patch_point_displacement = &displacement.patches;
    }
    if (options.parallel)
        inputs.decomposition = &decomposition;
    result.constraints = morph::build_constraints(mesh, setup, inputs);
    if (options.parallel)
        set_global_patch_points(mesh, decomposition, result.constraints.patches);
    const morph::Constraints& c = result.constraints;
    morph::check_duplicate_prescribed_points(mesh, c, foam.points.path.string());

    if (options.overwrite)
        result.output_instance = foam.points_instance;
    else
    {
        const std::vector<io::TimeDir> times = io::list_times(mesh_case);
        result.output_instance =
            io::next_time_name(times, foam.time, io::read_time_settings(case_dir));
    }
    if (options.parallel && options.vtk)
        throw InvalidInput("-vtk is not available with -parallel yet (reconstructPar, then "
                           "checkMeshQuality -vtk)");
#if !MESHMORPH_WITH_VTK
    if (options.vtk)
        throw InvalidInput("-vtk: this build has no VTK support (MESHMORPH_WITH_VTK=OFF)");
#endif
    result.timings.read = stage.seconds();
    log::info() << "Read case and " << dict_path.string() << " in "
                << format_seconds(result.timings.read) << " s";

    log_setup(c);

    // Quality before.
    stage.restart();
    CheckMeshSettings check_settings;
    // The per-cell scaled Jacobian is not a checkMesh check: only for the JSON and VTK
    // output (as in checkMeshQuality), it costs as much as the checks themselves.
    check_settings.scaled_jacobian = !options.json.empty() || options.vtk;
    // The topology does not change: one cell->faces addressing serves both checks.
    const CompactList cf = cell_faces(mesh);
    result.before =
        check_morph_mesh(mesh, cf, compute_geometry(mesh, cf), check_settings, decomposition);
    result.timings.check = stage.seconds();
    warn_if_broken(result.before, foam.points_dir);

    // Fit and evaluate, in steps.
    const Index n_fit = c.n_prescribed_points + c.n_slip_points;
    log::info() << "Method: " << describe(settings, n_fit);
    log::info() << "Steps: "
                << (needs_fit(settings) ? describe(step_settings)
                                        : "1 (ffd moves its control points once)");
    const morph::DeformationMaker make = [&](const Points& points)
    { return make_deformation(settings, points, n_fit); };
    const InvalidCells invalid_before{result.before.negative_volume_cells,
                                      result.before.incorrectly_oriented_face_pyramids};
    const morph::Decomposition* parts = options.parallel ? &decomposition : nullptr;
    morph::SteppedMorph stepped = morph::morph_in_steps(mesh, cf, c, step_settings, make,
                                                        needs_fit(settings), invalid_before, parts);
    result.steps = stepped.steps;
    for (const morph::StepRecord& s : stepped.steps)
    {
        result.timings.fit += s.fit_seconds;
        result.timings.evaluate += s.evaluate_seconds;
        result.timings.check += s.check_seconds;
        result.timings.untangle += s.untangle_seconds;
    }
    result.morph = std::move(stepped.last);
    result.morph.displacement = std::move(stepped.displacement);
    morph::measure_constraint_error(c, mesh.points, result.morph, parts);
    result.max_displacement = comm.max(max_norm(result.morph.displacement));
    log_fit(result, settings, global_count(decomposition, mesh.n_points(), true));

    // Quality after.
    stage.restart();
    result.valid_fraction = stepped.valid_fraction;
    if (stepped.valid_fraction < 1.0)
        log::warning() << "the motion is valid up to " << fmt(stepped.valid_fraction, 4)
                       << " of itself; beyond, "
                       << (step_settings.steps == 0
                               ? "even a step of 1/" + std::to_string(step_settings.max_steps) +
                                     " of it creates invalid cells"
                               : "a step creates invalid cells (try more steps, or steps auto)");
    PolyMesh moved = mesh;
    moved.points = std::move(stepped.points); // exactly the points stepped.geometry is of
    result.after = check_morph_mesh(moved, cf, stepped.geometry, check_settings, decomposition);
    result.timings.check += stage.seconds();
    if (comm.master()) // in a -parallel run, the other ranks hold only their part's report
    {
        std::ostringstream summary;
        print_quality_summary(summary, quality_json(result.before), quality_json(result.after));
        log::info() << "Mesh quality before and after the morph:\n" << summary.str();
    }
    const std::vector<std::string> reasons = refusal_reasons(result.before, result.after);
    if (!reasons.empty())
    {
        result.refusal = "the morphed mesh has " + reasons.front() +
                         (reasons.size() > 1 ? " and " + reasons.back() : std::string());
        if (!options.force)
        {
            result.refused = true; // the caller reports it (run_morph_mesh: exit status 3)
            return result;
        }
        log::warning() << "-force: writing although " << result.refusal;
    }

    // Write.
    stage.restart();
    parallel::collective(comm,
                         [&]
                         {
                             if (!options.overwrite)
                                 warn_if_replacing(mesh_case, result.output_instance, foam.region);
                             if (!options.parallel)
                                 warn_if_decomposed(case_dir);
                             result.points_file = write_morphed_points(
                                 options, moved.points, foam, mesh_case, result.output_instance);
                         });
    result.written = true;
    if (options.vtk)
        write_vtk(case_dir, options, moved, result);
    result.timings.write = stage.seconds();
    log::info() << "Wrote " << result.points_file.string() << " in "
                << format_seconds(result.timings.write) << " s";
    if (!result.vtk_file.empty())
        log::info() << "Wrote " << result.vtk_file.string()
                    << " (point data: displacement; cell data: nonOrthogonality, skewness, "
                       "aspectRatio)";
    return result;
}

std::string morph_json(const MorphResult& result, int exit_status)
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
    j["steps"] = nlohmann::json::array();
    for (const morph::StepRecord& s : result.steps)
        j["steps"].push_back({{"from", s.from},
                              {"to", s.to},
                              {"centres", s.centres},
                              {"globalResidual", s.max_global_residual},
                              {"negativeVolumeCells", s.invalid.negative_volume_cells},
                              {"incorrectlyOrientedFacePyramids", s.invalid.wrong_pyramids},
                              {"untangle",
                               {{"invalidCells", s.untangle.invalid_before},
                                {"pointsMoved", s.untangle.points_moved},
                                {"maxMove", s.untangle.max_move},
                                {"layers", s.untangle.layers},
                                {"stillInvalid", s.untangle.invalid_after},
                                {"seconds", s.untangle_seconds}}},
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
    MorphOptions morph;
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
        deformation_method_from_string(*m); // validate early: a usage error
        morph.method = *m;
    }
    morph.json = json_path;
    morph.vtk = vtk_requested(options);
    morph.vtk_file = vtk_file_argument(options);
    morph.force = options.found("force");
    morph.parallel = options.found("parallel");

    print_banner(out, {"morphMesh", options.command_line(), morph.case_dir.string()});
    const MorphResult result = morph_case(morph);
    if (!morph.json.empty() && parallel::Communicator::world().master())
    {
        io::write_file_atomic(morph.json,
                              morph_json(result, result.refused ? exit_refused : exit_ok));
        out << "Wrote " << morph.json.string() << "\n";
    }
    out << "\nTimings [s]: read " << format_seconds(result.timings.read) << ", fit "
        << format_seconds(result.timings.fit) << ", evaluate "
        << format_seconds(result.timings.evaluate) << ", check "
        << format_seconds(result.timings.check) << ", untangle "
        << format_seconds(result.timings.untangle) << ", write "
        << format_seconds(result.timings.write) << "\n";
    if (result.refused)
    {
        log::error() << result.refusal
                     << ". Nothing written: reduce the motion, change the method or use -force.";
        return exit_refused;
    }
    out << (result.after.mesh_ok()
                ? "Mesh OK."
                : "Failed " + std::to_string(result.after.failed_checks) + " mesh checks.")
        << "\n";
    print_end(out);
    return exit_ok;
}

} // namespace

int run_morph_mesh(int argc, const char* const argv[], std::ostream& out, std::ostream& err)
{
    const log::SinkScope log_to(log::stream_sink(out, err));
    const std::vector<OptionSpec> vtk =
        vtk_option_specs("morphMesh", "the displacement and quality");
    Options options(
        "morphMesh",
        "Morphs the polyMesh of an OpenFOAM case with a space deformation (RBF by default,\n"
        "IDW, DM-FFD or FFD) fitted to the boundary and handle prescriptions of\n"
        "system/morphDict, in steps refitted on the moved mesh ('steps auto': one step,\n"
        "halved while a step inverts cells), then checks the result like checkMesh.\n"
        "Without -overwrite only <next time>/polyMesh/points is written (read it with\n"
        "-latestTime); a morph that creates negative-volume cells or wrongly oriented face\n"
        "pyramids is not written unless -force.\n"
        "Conflicting prescriptions on shared points follow the dictionary's 'conflicts' rule\n"
        "(default fixed: such points do not move); handles override boundary prescriptions.",
        {{"case", "DIR", "Case directory (default: the current directory)"},
         {"dict", "FILE", "Alternative morphDict (relative to the case; default system/morphDict)"},
         {"region", "NAME",
          "Morph region NAME (constant/NAME/polyMesh, system/NAME/morphDict, "
          "<time>/NAME/pointDisplacement)"},
         {"time", "TIME", "Morph the mesh at this time (a time name or value, or constant)"},
         {"latestTime", "", "Morph the mesh at the latest time"},
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
          "directory"}},
        {{exit_ok, "morphed mesh written"},
         {exit_input_error, "bad option, dictionary, mesh or surface file; nothing written"},
         {exit_refused, "the morph creates invalid cells; nothing written (see -force)"},
         {exit_fit_failed, "the deformation could not be fitted; nothing written"},
         {exit_internal_error, "unexpected internal error"}});
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
    return run_guarded([&] { return morph_mesh_main(options, json_path, report_out); }, true,
                       report_failure);
}

} // namespace meshmorph::app
