// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/morph/morph_output.h"

#include <fstream>
#include <sstream>
#include <vector>

#include "meshmorph/core/config.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/case_instance.h"
#include "meshmorph/io/decomposed_case.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/temp_file.h"
#include "meshmorph/io/write_poly_mesh.h"
#if MESHMORPH_WITH_VTK
#include "meshmorph/io/vtk_writer.h"
#endif

namespace meshmorph::morph
{

namespace fs = std::filesystem;

namespace
{

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
    // A run killed while it wrote the orig left a temporary of it; the write below removes
    // such leftovers, but when the orig exists there is no write.
    io::remove_stale_temps(orig);
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

} // namespace

std::string morph_result_note(const std::string& instance)
{
    return std::string(morph_note_prefix) + " from the points of " + instance;
}

bool is_morph_result(const io::FoamHeader& header)
{
    return header.note.rfind(morph_note_prefix, 0) == 0;
}

//! The morphed points, and with -overwrite the original kept first; a failure removes what
//! this run created, so a failed write leaves the case as it was.
fs::path write_morphed_points(const MorphOptions& options, const Points& points,
                              const io::FoamPolyMesh& foam, const fs::path& mesh_case,
                              const std::string& instance)
{
    // Never written, not even with -force: OpenFOAM cannot read such a file back, and
    // checkMesh stops on it with a floating-point exception.
    for (Eigen::Index i = 0; i < points.rows(); ++i)
        if (!points.row(i).allFinite())
            throw InvalidInput("the morph moved point " + std::to_string(i) +
                               " to a coordinate that is not finite (an overflow): nothing "
                               "written; check the size of the prescribed motion");
    const fs::path orig = options.overwrite ? keep_original_points(foam.points.path) : fs::path();
    io::FoamFileInfo like = foam.points;
    like.header.note = morph_result_note(foam.points_instance);
    try
    {
        return io::write_points(points, like, mesh_case, instance, foam.region);
    }
    catch (const Error&)
    {
        std::error_code ignored;
        if (!orig.empty())
            fs::remove(orig, ignored);
        throw;
    }
}

//! Without -overwrite the morph replaces points already at the time it writes (an earlier
//! morph's, or another tool's such as reconstructPar's): say so.
void warn_if_replacing(const fs::path& case_dir, const std::string& instance,
                       const std::string& region)
{
    const fs::path dir = io::poly_mesh_dir(case_dir, instance, region);
    for (const char* name : {"points", "points.gz"})
        if (fs::exists(dir / name))
            log::warning() << "replacing " << (dir / name).string()
                           << ", already at the time this morph writes (to keep it, move it "
                              "away first)";
}

//! A decomposed case keeps its own copy of the mesh in every processor directory: a serial
//! morph changes only the undecomposed mesh, and a parallel run would use the old one.
void warn_if_decomposed(const fs::path& case_dir)
{
    const std::vector<std::string> dirs = io::processor_directories(case_dir);
    if (dirs.empty())
        return;
    log::warning() << "the case is decomposed (" << dirs.front()
                   << (dirs.size() > 1 ? " ... " + dirs.back() : std::string())
                   << "): this morph changes only the undecomposed mesh; the processor "
                      "directories still hold the old mesh (decompose again, e.g. "
                      "decomposePar -force, before a parallel run)";
}

//! -vtk: the morphed mesh with the displacement and the quality fields.
void write_vtk(const fs::path& case_dir, const MorphOptions& options, const PolyMesh& moved,
               MorphResult& result)
{
#if MESHMORPH_WITH_VTK
    result.vtk_file =
        options.vtk_file.empty()
            ? io::default_vtk_file(case_dir, "morphMesh", options.region, result.output_instance)
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

} // namespace meshmorph::morph
