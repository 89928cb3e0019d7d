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
#include "meshmorph/core/config.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/case_instance.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/read_poly_mesh.h"
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
    std::ostringstream out;
    out << "/*--------------------------------*- C++ -*----------------------------------*\\\n"
        << "  Written by meshMorph " << MESHMORPH_VERSION << " (checkMeshQuality)\n"
        << "\\*---------------------------------------------------------------------------*/\n"
        << "FoamFile\n{\n"
        << "    version     2.0;\n"
        << "    format      ascii;\n"
        << "    class       " << cls << ";\n"
        << "    location    \"" << location << "\";\n"
        << "    object      " << object << ";\n"
        << "}\n"
        << "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n";
    return out.str();
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

//! checkMeshQuality after its options are parsed; throws on errors (run_guarded reports
//! them).
int check_mesh_quality_main(const Options& options, std::ostream& out)
{
    if (options.found("time") && options.found("latestTime"))
        throw UsageError("-time and -latestTime are mutually exclusive");
    fs::path case_dir = fs::absolute(options.value_or("case", ".")).lexically_normal();
    if (!case_dir.has_filename() && case_dir.has_parent_path())
        case_dir = case_dir.parent_path();
    if (!fs::is_directory(case_dir))
        throw IoError("case directory " + case_dir.string() + " does not exist");
    const bool quiet = options.found("quiet");
    if (quiet)
        log::set_level(log::Level::warning); // restored by run_check_mesh_quality's SinkScope
    std::ostringstream discard;
    std::ostream& info = quiet ? discard : out;
    print_banner(info, {"checkMeshQuality", options.command_line(), case_dir.string()});
    StageTimer timer;

    io::PolyMeshReadOptions read_options;
    read_options.region = region_option(options);
    if (options.found("latestTime"))
        read_options.time = io::TimeSelection::latest_time();
    else if (const std::optional<std::string> t = options.get("time"))
        read_options.time = io::TimeSelection::at(*t);
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
            read_mesh_quality_dict(case_dir / "system" / read_options.region / "meshQualityDict");

    const io::FoamPolyMesh foam = io::read_poly_mesh(case_dir, read_options);
    const PolyMesh& mesh = foam.mesh;
    settings.time_name = foam.time;
    timer.lap("Read mesh (" + std::to_string(mesh.n_cells) + " cells)");

    const CompactList cf = cell_faces(mesh);
    const MeshGeometry geometry = compute_geometry(mesh, cf);
    QualityReport report = check_mesh(mesh, cf, geometry, settings);
    out << "Time = " << foam.time << "\n\n" << report.text;
    info << "\n";
    timer.lap("Checked mesh");

    if (settings.report_sets)
    {
        const std::vector<fs::path> files =
            write_mesh_sets(report.sets, case_dir, foam.points_instance, read_options.region);
        std::string written =
            "Wrote " + std::to_string(files.size()) + " sets to " +
            (case_dir / foam.points_instance / read_options.region / "polyMesh" / "sets").string();
        // One timing line for all that -writeSets writes.
        if (!report.cell_to_region.empty())
            written += " and " + write_cell_to_region(report.cell_to_region, case_dir, foam.time,
                                                      read_options.region)
                                     .string();
        timer.lap(written);
    }
    if (vtk_requested(options))
    {
#if MESHMORPH_WITH_VTK
        fs::path vtk = vtk_file_argument(options);
        if (vtk.empty())
            vtk = default_vtk_file(case_dir, "checkMeshQuality", read_options.region, foam.time);
        std::vector<io::VtkField> fields;
        fields.emplace_back("nonOrthogonality", report.cell_non_orthogonality);
        fields.emplace_back("skewness", report.cell_skewness);
        fields.emplace_back("aspectRatio", report.cell_aspect_ratio);
        fields.emplace_back("volume", geometry.cell_volumes);
        fields.emplace_back("determinant", report.cell_determinant);
        if (report.cell_scaled_jacobian.size() == mesh.n_cells)
            fields.emplace_back("scaledJacobian", report.cell_scaled_jacobian);
        { // a read-only or full file system is an input error naming the directory
            std::error_code ec;
            fs::create_directories(vtk.parent_path(), ec);
            if (ec)
                throw IoError("Cannot create directory " + vtk.parent_path().string() + ": " +
                              ec.message());
        }
        io::write_vtu(vtk, mesh, {}, fields);
        timer.lap("Wrote " + vtk.string());
#else
        throw UsageError("-vtk: this build has no VTK support (MESHMORPH_WITH_VTK=OFF)");
#endif
    }
    if (const std::optional<std::string> json_path = options.get("json"))
    {
        nlohmann::json j = quality_json(report);
        j["case"] = case_dir.string();
        j["time"] = foam.time;
        j["region"] = read_options.region;
        const std::string text = j.dump(2) + "\n";
        io::write_file_atomic(fs::absolute(*json_path), text);
        timer.lap("Wrote " + *json_path);
    }
    if (!quiet)
        print_end(out);
    return report.mesh_ok() ? exit_ok : exit_checks_failed;
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
         {"quiet", "", "Print only the report (no banner or timings)"}},
        {{exit_ok, "the mesh passed every check (\"Mesh OK.\")"},
         {exit_checks_failed, "some checks failed (\"Failed N mesh checks.\")"},
         {exit_input_error,
          "input error: bad option, missing or malformed case files or dictionaries"},
         {exit_internal_error, "unexpected internal error"}});
    if (const std::optional<int> code = parse_command_line(options, argc, argv, out))
        return *code;
    return run_guarded([&] { return check_mesh_quality_main(options, out); }, false);
}

} // namespace meshmorph::app
