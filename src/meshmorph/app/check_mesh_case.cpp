// SPDX-License-Identifier: GPL-3.0-or-later
// checkMeshQuality: options, case reading, report, sets, VTK and JSON output.
#include "meshmorph/app/check_mesh_case.h"

#include <cstdlib>
#include <fstream>
#include <ostream>
#include <regex>
#include <sstream>

#include "meshmorph/app/banner.h"
#include "meshmorph/app/options.h"
#include "meshmorph/app/parallel_run.h"
#include "meshmorph/core/config.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/io/case_instance.h"
#include "meshmorph/io/decomposed_case.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/foam_header.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/parallel/collective.h"
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

fs::path openfoam_etc_dir()
{
    if (const char* dir = std::getenv("WM_PROJECT_DIR"); dir && *dir)
        return fs::path(dir) / "etc";
    return "/usr/share/openfoam/etc";
}

//! Replace `#includeEtc "X"` by `#include "<etc>/X"` when that file exists (the dictionary
//! parser does not know the OpenFOAM installation). Line numbers are preserved.
std::string resolve_include_etc(const std::string& text)
{
    static const std::regex include_etc(R"re(#includeEtc\s+"([^"]+)")re");
    std::string result;
    std::sregex_iterator it(text.begin(), text.end(), include_etc), end;
    std::size_t last = 0;
    for (; it != end; ++it)
    {
        const std::smatch& m = *it;
        const fs::path file = openfoam_etc_dir() / m[1].str();
        result.append(text, last, static_cast<std::size_t>(m.position(0)) - last);
        if (fs::exists(file))
            result += "#include \"" + file.string() + "\"";
        else
            result += m.str(0);
        last = static_cast<std::size_t>(m.position(0) + m.length(0));
    }
    result.append(text, last, std::string::npos);
    return result;
}

//! An ascii FoamFile header, its divider line and the blank line after it, as OpenFOAM
//! writes them (with our banner).
std::string file_header(const std::string& cls, const std::string& location,
                        const std::string& object)
{
    io::FoamHeader header;
    header.class_name = cls;
    header.location = location;
    header.object = object;
    return io::format_header(header, io::framed_banner(std::string("Written by meshMorph ") +
                                                       MESHMORPH_VERSION + " (checkMeshQuality)"));
}

} // namespace

MeshQualitySettings read_mesh_quality_dict(const fs::path& path)
{
    const io::FileBuffer file = io::read_foam_file(path);
    const io::FoamDictionary dict =
        io::parse_dictionary(resolve_include_etc(file.data), file.path.string());
    MeshQualitySettings q;
    q.max_non_ortho = dict.get<double>("maxNonOrtho");
    q.min_vol = dict.get<double>("minVol");
    q.min_tet_quality = dict.get<double>("minTetQuality");
    q.max_concave = dict.get<double>("maxConcave");
    q.min_area = dict.get<double>("minArea");
    q.max_internal_skewness = dict.get<double>("maxInternalSkewness");
    q.max_boundary_skewness = dict.get<double>("maxBoundarySkewness");
    q.min_face_weight = dict.get<double>("minFaceWeight");
    q.min_vol_ratio = dict.get<double>("minVolRatio");
    q.min_twist = dict.get<double>("minTwist");
    q.min_triangle_twist = dict.get<double>("minTriangleTwist");
    q.min_face_flatness = dict.get_or<double>("minFaceFlatness", -1.0);
    // OpenFOAM aborts on an enabled flatness limit outside [0, 1]; so do we.
    if (q.min_face_flatness > -constants::small &&
        (q.min_face_flatness < 0 || q.min_face_flatness > 1))
        throw dict.entry("minFaceFlatness")
            .error("should be in [0..1] but is " + format_scalar(q.min_face_flatness, 6));
    q.min_determinant = dict.get<double>("minDeterminant");
    return q;
}

int read_write_precision(const fs::path& case_dir)
{
    const fs::path path = case_dir / "system" / "controlDict";
    if (!io::foam_file_exists(path))
        return 6;
    const io::FileBuffer file = io::read_foam_file(path);
    // Only writePrecision is read: the tutorials' function objects (#includeFunc) and
    // computed entries elsewhere in the file do not matter.
    io::ParseOptions lenient;
    lenient.skip_unsupported = true;
    const io::FoamDictionary dict =
        io::parse_dictionary(resolve_include_etc(file.data), file.path.string(), lenient);
    const int precision = dict.get_or<int>("writePrecision", 6);
    if (precision < 1 || precision > 30)
        throw dict.entry("writePrecision").error("writePrecision must be in [1, 30]");
    return precision;
}

std::string mesh_set_file_text(const MeshSet& set, const std::string& location)
{
    const char* cls = set.kind == MeshSet::Kind::face
                          ? "faceSet"
                          : (set.kind == MeshSet::Kind::cell ? "cellSet" : "pointSet");
    std::ostringstream out;
    out << file_header(cls, location, set.name) << "\n" << set.labels.size() << "\n(\n";
    for (Index label : set.labels)
        out << label << "\n";
    out << ")\n\n\n"
        << "// ************************************************************************* //\n";
    return out.str();
}

std::vector<fs::path> write_mesh_sets(const std::vector<MeshSet>& sets, const fs::path& case_dir,
                                      const std::string& instance, const std::string& region)
{
    std::vector<fs::path> written;
    if (sets.empty())
        return written;
    const fs::path dir = case_dir / instance / region / "polyMesh" / "sets";
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw IoError("cannot create directory " + dir.string() + ": " + ec.message());
    for (const MeshSet& set : sets)
        written.push_back(io::write_file_atomic(
            dir / set.name,
            mesh_set_file_text(set, (fs::path(instance) / region / "polyMesh" / "sets").string())));
    return written;
}

std::string cell_to_region_file_text(const std::vector<Index>& cell_to_region,
                                     const std::string& location)
{
    std::ostringstream out;
    out << file_header("labelList", location, "cellToRegion");
    // UList::writeList with a short-list length of 10 (the regions differ, so the list is
    // never written as uniform `N{v}`).
    const std::size_t n = cell_to_region.size();
    if (n <= 10)
    {
        out << n << "(";
        for (std::size_t i = 0; i < n; ++i)
            out << (i ? " " : "") << cell_to_region[i];
        out << ")";
    }
    else
    {
        out << "\n" << n << "\n(\n";
        for (Index label : cell_to_region)
            out << label << "\n";
        out << ")\n";
    }
    out << "\n\n// ************************************************************************* //\n";
    return out.str();
}

fs::path write_cell_to_region(const std::vector<Index>& cell_to_region, const fs::path& case_dir,
                              const std::string& time, const std::string& region)
{
    const fs::path dir = case_dir / time / region;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw IoError("cannot create directory " + dir.string() + ": " + ec.message());
    const std::string location = region.empty() ? time : time + "/" + region;
    return io::write_file_atomic(dir / "cellToRegion",
                                 cell_to_region_file_text(cell_to_region, location));
}

namespace
{

//! The settings of the checks: the options, controlDict's writePrecision and, with
//! -meshQuality, meshQualityDict (read from the case, also in a -parallel run).
CheckMeshSettings check_settings(const Options& options, const fs::path& case_dir,
                                 const std::string& region)
{
    CheckMeshSettings settings;
    settings.all_geometry = options.found("allGeometry");
    settings.all_topology = options.found("allTopology");
    settings.no_topology = options.found("noTopology");
    settings.report_sets = options.found("writeSets");
    // The scaled Jacobian is reported in the JSON and VTK outputs only.
    settings.scaled_jacobian = options.found("json") || vtk_requested(options);
    settings.write_precision = read_write_precision(case_dir);
    if (options.found("meshQuality"))
        settings.mesh_quality =
            read_mesh_quality_dict(case_dir / "system" / region / "meshQualityDict");
    return settings;
}

io::PolyMeshReadOptions read_options_of(const Options& options)
{
    io::PolyMeshReadOptions read_options;
    read_options.region = region_option(options);
    if (options.found("latestTime"))
        read_options.time = io::TimeSelection::latest_time();
    else if (const std::optional<std::string> t = options.get("time"))
        read_options.time = io::TimeSelection::at(*t);
    return read_options;
}

//! The mesh, its geometry and its report (in a -parallel run: this rank's part, and the
//! report of the whole mesh on the master).
struct CheckedMesh
{
    io::FoamPolyMesh foam;
    CompactList cell_faces;
    MeshGeometry geometry;
    QualityReport local;  //!< this rank's sets and fields
    QualityReport report; //!< the report to print (the whole mesh)
};

void check(const CheckMeshSettings& settings, const parallel::Communicator* comm, CheckedMesh& m)
{
    m.cell_faces = cell_faces(m.foam.mesh);
    m.geometry = compute_geometry(m.foam.mesh, m.cell_faces);
    if (!comm)
    {
        m.local = check_mesh(m.foam.mesh, m.cell_faces, m.geometry, settings);
        m.report = m.local;
        return;
    }
    ProcessorFaces processors = exchange_processor_faces(m.foam.mesh, m.geometry, *comm);
    std::vector<Index> addressing;
    parallel::collective(*comm, [&] { addressing = io::read_point_addressing(m.foam); });
    const Index global_points = io::global_point_count(addressing, *comm);
    m.local = check_mesh(m.foam.mesh, m.cell_faces, m.geometry, settings, &processors);
    m.report = reduce_report(m.local, m.foam.mesh, settings, processors, global_points);
}

//! -writeSets: the offending sets (and cellToRegion) of this rank, where checkMesh writes
//! them (in a -parallel run, in the processor directory).
void write_sets(const CheckedMesh& m, const fs::path& mesh_case, const std::string& region,
                StageTimer& timer)
{
    const std::vector<fs::path> files =
        write_mesh_sets(m.local.sets, mesh_case, m.foam.points_instance, region);
    std::string written =
        "Wrote " + std::to_string(files.size()) + " sets to " +
        (mesh_case / m.foam.points_instance / region / "polyMesh" / "sets").string();
    // One timing line for all that -writeSets writes.
    if (!m.local.cell_to_region.empty())
        written +=
            " and " +
            write_cell_to_region(m.local.cell_to_region, mesh_case, m.foam.time, region).string();
    timer.lap(written);
}

void write_vtk(const Options& options, const CheckedMesh& m, const fs::path& case_dir,
               const std::string& region, StageTimer& timer)
{
#if MESHMORPH_WITH_VTK
    fs::path vtk = vtk_file_argument(options);
    if (vtk.empty())
        vtk = io::default_vtk_file(case_dir, "checkMeshQuality", region, m.foam.time);
    const QualityReport& r = m.local;
    std::vector<io::VtkField> fields;
    fields.emplace_back("nonOrthogonality", r.cell_non_orthogonality);
    fields.emplace_back("skewness", r.cell_skewness);
    fields.emplace_back("aspectRatio", r.cell_aspect_ratio);
    fields.emplace_back("volume", m.geometry.cell_volumes);
    fields.emplace_back("determinant", r.cell_determinant);
    if (r.cell_scaled_jacobian.size() == m.foam.mesh.n_cells)
        fields.emplace_back("scaledJacobian", r.cell_scaled_jacobian);
    { // a read-only or full file system is an input error naming the directory
        std::error_code ec;
        fs::create_directories(vtk.parent_path(), ec);
        if (ec)
            throw IoError("Cannot create directory " + vtk.parent_path().string() + ": " +
                          ec.message());
    }
    io::write_vtu(vtk, m.foam.mesh, {}, fields);
    timer.lap("Wrote " + vtk.string());
#else
    (void)options, (void)m, (void)case_dir, (void)region, (void)timer;
    throw UsageError("-vtk: this build has no VTK support (MESHMORPH_WITH_VTK=OFF)");
#endif
}

void write_json(const std::string& json_path, const CheckedMesh& m, const fs::path& case_dir,
                const std::string& region, int ranks, StageTimer& timer)
{
    nlohmann::json j = quality_json(m.report);
    j["case"] = case_dir.string();
    j["time"] = m.foam.time;
    j["region"] = region;
    if (ranks > 1)
        j["parallel"] = ranks;
    io::write_file_atomic(fs::absolute(json_path), j.dump(2) + "\n");
    timer.lap("Wrote " + json_path);
}

fs::path case_directory(const Options& options)
{
    fs::path case_dir = fs::absolute(options.value_or("case", ".")).lexically_normal();
    if (!case_dir.has_filename() && case_dir.has_parent_path())
        case_dir = case_dir.parent_path();
    if (!fs::is_directory(case_dir))
        throw IoError("case directory " + case_dir.string() + " does not exist");
    return case_dir;
}

//! checkMeshQuality after its options are parsed; throws on errors (run_guarded reports
//! them). With -parallel every rank runs it; the master prints and writes the JSON.
int check_mesh_quality_main(const Options& options, std::ostream& out)
{
    if (options.found("time") && options.found("latestTime"))
        throw UsageError("-time and -latestTime are mutually exclusive");
    const bool parallel_run = options.found("parallel");
    if (parallel_run && vtk_requested(options))
        throw UsageError("-vtk is not available with -parallel yet (reconstructPar, then "
                         "checkMeshQuality -vtk)");
    const parallel::Communicator& comm = parallel::Communicator::world();
    const fs::path case_dir = case_directory(options);
    const bool quiet = options.found("quiet");
    if (quiet)
        log::set_level(log::Level::warning); // restored by run_check_mesh_quality's SinkScope
    std::ostringstream discard;
    std::ostream& info = quiet || !comm.master() ? discard : out;
    std::ostream& report_out = comm.master() ? out : discard;
    print_banner(info, {"checkMeshQuality", options.command_line(), case_dir.string()});
    StageTimer timer;

    const io::PolyMeshReadOptions read_options = read_options_of(options);
    const std::string& region = read_options.region;
    CheckMeshSettings settings;
    CheckedMesh m;
    const fs::path mesh_case =
        parallel_run ? io::processor_case(case_dir, comm, "checkMeshQuality") : case_dir;
    parallel::collective(comm,
                         [&]
                         {
                             settings = check_settings(options, case_dir, region);
                             m.foam = io::read_poly_mesh(mesh_case, read_options);
                         });
    settings.time_name = m.foam.time;
    timer.lap("Read mesh (" + std::to_string(m.foam.mesh.n_cells) + " cells" +
              (parallel_run ? " on processor0" : "") + ")");

    check(settings, parallel_run ? &comm : nullptr, m);
    report_out << "Time = " << m.foam.time << "\n\n" << m.report.text;
    info << "\n";
    timer.lap("Checked mesh");

    if (settings.report_sets)
        parallel::collective(comm, [&] { write_sets(m, mesh_case, region, timer); });
    if (vtk_requested(options))
        write_vtk(options, m, case_dir, region, timer);
    if (const std::optional<std::string> json_path = options.get("json"))
        parallel::on_master(comm, [&]
                            { write_json(*json_path, m, case_dir, region, comm.size(), timer); });
    if (!quiet)
        print_end(info);
    // Every rank exits with the master's verdict on the whole mesh.
    const Index failed = Index(comm.max(std::int64_t(comm.master() ? m.report.failed_checks : 0)));
    return failed == 0 ? exit_ok : exit_checks_failed;
}

} // namespace

int run_check_mesh_quality(int argc, const char* const argv[], std::ostream& out, std::ostream& err)
{
    const log::SinkScope log_to(log::stream_sink(out, err));
    const std::vector<OptionSpec> vtk =
        vtk_option_specs("checkMeshQuality", "per-cell quality fields");
    Options options(
        "checkMeshQuality",
        "Checks the validity and quality of an OpenFOAM polyMesh like OpenFOAM's checkMesh\n"
        "(same checks, formulas and report text as v1912), optionally writing the sets of\n"
        "offending faces/cells, a VTK file with per-cell quality fields and a JSON summary.",
        {vtk[0],
         vtk[1],
         {"case", "DIR", "Case directory (default: the current directory)"},
         {"region", "NAME",
          "Check region NAME (constant/NAME/polyMesh; system/NAME/meshQualityDict)"},
         {"time", "TIME", "Check the mesh at this time (a time name or value, or constant)"},
         {"latestTime", "", "Check the mesh at the latest time"},
         {"allGeometry", "", "Include the extra geometry checks (face tets, flatness, ...)"},
         {"allTopology", "", "Include the extra topology checks (cell zip-up, face-face)"},
         {"noTopology", "", "Skip the topology checks"},
         {"meshQuality", "", "Also check against system/meshQualityDict (snappyHexMesh's)"},
         {"writeSets", "",
          "Write the offending faces/cells/points as OpenFOAM sets to "
          "<instance>/polyMesh/sets"},
         {"json", "FILE", "Write the results as JSON (path relative to the working directory)"},
         {"parallel", "",
          "Check the decomposed case (processor*/) under mpirun, one rank per processor "
          "directory; the report is that of the whole mesh"},
         {"quiet", "", "Print only the report (no banner or timings)"}},
        {{exit_ok, "the mesh passed every check (\"Mesh OK.\")"},
         {exit_checks_failed, "some checks failed (\"Failed N mesh checks.\")"},
         {exit_input_error,
          "input error: bad option, missing or malformed case files or dictionaries"},
         {exit_internal_error, "unexpected internal error"}});
    if (const std::optional<int> code = parse_command_line(options, argc, argv, out))
        return *code;
    std::optional<ParallelRun> run; // -parallel: MPI for the whole run
    try
    {
        run.emplace(options.found("parallel"));
    }
    catch (const Error& e)
    {
        log::error() << e.what();
        return exit_input_error;
    }
    return run_guarded([&] { return check_mesh_quality_main(options, out); }, false);
}

} // namespace meshmorph::app
