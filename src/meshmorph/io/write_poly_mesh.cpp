// SPDX-License-Identifier: GPL-3.0-or-later
// polyMesh writers: each file is composed in memory, then written atomically.
#include "meshmorph/io/write_poly_mesh.h"

#include <system_error>
#include <vector>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/boundary_io.h"
#include "meshmorph/io/case_instance.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/foam_lists.h"
#include "meshmorph/io/temp_file.h"

namespace meshmorph::io
{
namespace fs = std::filesystem;

namespace
{

FoamFormat format_of(const FoamFileInfo& like, const PolyMeshWriteOptions& options)
{
    return options.format ? *options.format : like.header.format;
}

bool compress_of(const FoamFileInfo& like, const PolyMeshWriteOptions& options)
{
    return options.compress ? *options.compress : like.is_compressed;
}

int label_bytes_of(const FoamFileInfo& like, const PolyMeshWriteOptions& options)
{
    if (options.label_bytes == 4 || options.label_bytes == 8)
        return options.label_bytes;
    if (options.label_bytes != 0)
        throw InvalidInput("label size must be 4 or 8 bytes, not " +
                           std::to_string(options.label_bytes));
    return like.header.is_binary() ? like.header.label_bytes : static_cast<int>(sizeof(Index));
}

// The header to write: `like`'s, with format, location, object and arch updated.
FoamHeader make_header(const FoamFileInfo& like, const PolyMeshWriteOptions& options,
                       const std::string& object, const std::string& location)
{
    FoamHeader h = like.header;
    h.format = format_of(like, options);
    h.object = object;
    h.location = location;
    if (h.version.empty())
        h.version = "2.0";
    if (h.is_binary())
    {
        h.label_bytes = label_bytes_of(like, options);
        h.scalar_bytes = 8; // meshmorph always writes doubles
        h.arch = arch_string(h.label_bytes, h.scalar_bytes);
    }
    else
        h.arch.clear();
    return h;
}

void create_dirs(const fs::path& dir)
{
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw IoError("Cannot create directory " + dir.string() + ": " + ec.message());
}

fs::path write_file(const fs::path& path, const FoamHeader& header, const std::string& body,
                    bool compress)
{
    std::string text = format_header(header);
    text.reserve(text.size() + body.size() + 128);
    text += body;
    text += format_footer();
    WriteFileOptions wo;
    wo.compress = compress;
    return write_file_atomic(path, text, wo);
}

std::string mesh_note(const PolyMesh& mesh)
{
    return "nPoints:" + std::to_string(mesh.n_points()) +
           "  nCells:" + std::to_string(mesh.n_cells) +
           "  nFaces:" + std::to_string(mesh.n_faces()) +
           "  nInternalFaces:" + std::to_string(mesh.n_internal_faces());
}

void write_zone_file(const std::vector<Zone>& zones, const std::optional<FoamFileInfo>& like,
                     const fs::path& dir, const std::string& object, const std::string& location,
                     const PolyMeshWriteOptions& options, FoamFormat default_format)
{
    if (zones.empty() && !like)
        return;
    const FoamFileInfo info = like ? *like : default_file_info(object, default_format);
    const FoamHeader h = make_header(info, options, object, location);
    write_file(dir / object, h, format_zones(zones, h.format, h.label_bytes),
               compress_of(info, options));
}

} // namespace

std::string poly_mesh_location(const std::string& instance, const std::string& region)
{
    return poly_mesh_dir({}, instance, region).generic_string();
}

FoamFileInfo default_file_info(const std::string& object, FoamFormat format, bool compress)
{
    FoamFileInfo info;
    info.header.version = "2.0";
    info.header.format = format;
    info.header.object = object;
    info.header.label_bytes = static_cast<int>(sizeof(Index));
    info.header.scalar_bytes = 8;
    if (object == "points")
        info.header.class_name = "vectorField";
    else if (object == "faces")
        info.header.class_name = format == FoamFormat::binary ? "faceCompactList" : "faceList";
    else if (object == "owner" || object == "neighbour")
        info.header.class_name = "labelList";
    else if (object == "boundary")
        info.header.class_name = "polyBoundaryMesh";
    else
        info.header.class_name = "regIOobject"; // zones, as OpenFOAM v1912 writes them
    info.is_compressed = compress;
    return info;
}

FoamPolyMesh default_poly_mesh_files(FoamFormat format, bool compress)
{
    FoamPolyMesh m;
    m.points = default_file_info("points", format, compress);
    m.faces = default_file_info("faces", format, compress);
    m.owner = default_file_info("owner", format, compress);
    m.neighbour = default_file_info("neighbour", format, compress);
    // The mesh writers never compress `boundary` (docs/polymesh-format.md §7).
    m.boundary = default_file_info("boundary", format, false);
    return m;
}

fs::path write_points_file(const Points& points, const FoamFileInfo& like, const fs::path& path,
                           const std::string& location, const PolyMeshWriteOptions& options)
{
    FoamFileInfo info = like;
    if (info.header.class_name.empty())
        info.header.class_name = "vectorField";
    const FoamHeader h = make_header(info, options, "points", location);
    std::string body;
    append_vector_list(body, points, h.format, options.precision);
    return write_file(path, h, body, compress_of(like, options));
}

fs::path write_points(const Points& points, const FoamFileInfo& like, const fs::path& case_dir,
                      const std::string& instance, const std::string& region,
                      const PolyMeshWriteOptions& options)
{
    const fs::path dir = poly_mesh_dir(case_dir, instance, region);
    const std::string location = poly_mesh_location(instance, region);
    fs::path top; // the outermost directory of `dir` that does not exist yet
    for (fs::path d = dir; d != case_dir && d.has_relative_path() && !fs::exists(d);
         d = d.parent_path())
        top = d;
    if (top.empty())
    {
        if (foam_file_exists(dir / "tetBasePtIs"))
            log::warning() << (dir / "tetBasePtIs").string()
                           << " depends on the point positions and is now stale; remove it if "
                              "OpenFOAM reports tet decomposition problems";
        return write_points_file(points, like, dir / "points", location, options);
    }
    // New directories appear complete or not at all: built under a hidden name, then
    // renamed. A failed or killed write leaves no empty <time>/polyMesh that the next run or
    // OpenFOAM would take for a time (a killed one leaves a hidden temporary, removed by
    // the next write of the same directory).
    remove_stale_temps(top);
    const fs::path staging = temp_path_for(top);
    const fs::path staged_dir = staging / fs::relative(dir, top);
    try
    {
        try
        {
            create_dirs(staged_dir);
        }
        catch (const IoError& e)
        {
            throw IoError("Cannot write " + (dir / "points").string() + ": " + e.what());
        }
        fs::path written;
        try
        {
            written = write_points_file(points, like, staged_dir / "points", location, options);
        }
        catch (const IoError& e)
        {
            throw IoError("Cannot write " + (dir / "points").string() + ": " + e.what());
        }
        std::error_code ec;
        fs::rename(staging, top, ec);
        if (ec)
            throw IoError("Cannot write " + (dir / written.filename()).string() + ": rename of " +
                          staging.string() + " failed: " + ec.message());
        sync_directory(top.parent_path());
        return dir / written.filename();
    }
    catch (const Error&)
    {
        std::error_code ignored;
        fs::remove_all(staging, ignored);
        throw;
    }
}

fs::path write_poly_mesh_dir(const PolyMesh& mesh, const FoamPolyMesh& like, const fs::path& dir,
                             const std::string& location, const PolyMeshWriteOptions& options)
{
    create_dirs(dir);
    write_points_file(mesh.points, like.points, dir / "points", location, options);

    // faces: keep the class when the format is unchanged, else OpenFOAM's choice.
    {
        FoamFileInfo info = like.faces;
        const FoamFormat format = format_of(info, options);
        if (info.header.class_name.empty() || format != info.header.format)
            info.header.class_name = format == FoamFormat::binary ? "faceCompactList" : "faceList";
        const FoamHeader h = make_header(info, options, "faces", location);
        std::string body;
        if (h.class_name == "faceCompactList")
        {
            if (h.is_binary())
                append_face_list(body, mesh.faces, FoamFormat::binary, h.label_bytes);
            else
            {
                append_label_list(body, mesh.faces.offsets, FoamFormat::ascii);
                append_label_list(body, mesh.faces.values, FoamFormat::ascii);
            }
        }
        else
        {
            if (h.is_binary())
            {
                // A binary faceList: ASCII skeleton, each face its own binary block.
                body += '\n';
                body += std::to_string(mesh.n_faces());
                body += "\n(";
                for (Index f = 0; f < mesh.n_faces(); ++f)
                {
                    const std::span<const Index> face = mesh.faces[f];
                    append_label_list(body, std::vector<Index>(face.begin(), face.end()),
                                      FoamFormat::binary, h.label_bytes);
                }
                body += "\n)";
            }
            else
                append_face_list(body, mesh.faces, FoamFormat::ascii);
        }
        write_file(dir / "faces", h, body, compress_of(info, options));
    }

    const std::string note = mesh_note(mesh);
    const auto write_labels = [&](const FoamFileInfo& like_file, const std::string& object,
                                  const std::vector<Index>& values)
    {
        FoamFileInfo info = like_file;
        if (info.header.class_name.empty())
            info.header.class_name = "labelList";
        FoamHeader h = make_header(info, options, object, location);
        h.note = note;
        std::string body;
        append_label_list(body, values, h.format, h.label_bytes);
        write_file(dir / object, h, body, compress_of(info, options));
    };
    write_labels(like.owner, "owner", mesh.owner);
    write_labels(like.neighbour, "neighbour", mesh.neighbour);

    {
        FoamFileInfo info = like.boundary;
        if (info.header.class_name.empty())
            info.header.class_name = "polyBoundaryMesh";
        const FoamHeader h = make_header(info, options, "boundary", location);
        write_file(dir / "boundary", h, format_boundary(mesh.patches), compress_of(info, options));
    }

    const FoamFormat zone_format = format_of(like.points, options);
    write_zone_file(mesh.point_zones, like.point_zones, dir, "pointZones", location, options,
                    zone_format);
    write_zone_file(mesh.face_zones, like.face_zones, dir, "faceZones", location, options,
                    zone_format);
    write_zone_file(mesh.cell_zones, like.cell_zones, dir, "cellZones", location, options,
                    zone_format);
    return dir;
}

fs::path write_poly_mesh(const PolyMesh& mesh, const FoamPolyMesh& like, const fs::path& case_dir,
                         const std::string& instance, const std::string& region,
                         const PolyMeshWriteOptions& options)
{
    return write_poly_mesh_dir(mesh, like, poly_mesh_dir(case_dir, instance, region),
                               poly_mesh_location(instance, region), options);
}

} // namespace meshmorph::io
