// SPDX-License-Identifier: GPL-3.0-or-later
// polyMesh reader: one file at a time (its buffer is released before the next is read, to
// keep peak memory near file + mesh), validated as docs/polymesh-format.md §5-6 require.
#include "meshmorph/io/read_poly_mesh.h"

#include <algorithm>
#include <initializer_list>
#include <limits>
#include <string_view>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/boundary_io.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/foam_lists.h"
#include "meshmorph/io/foam_tokenizer.h"

namespace meshmorph::io
{
namespace fs = std::filesystem;

namespace
{

// One file in memory with its tokenizer positioned after the FoamFile header.
struct OpenFile
{
    explicit OpenFile(const fs::path& path) : buffer(path) {}
    MappedFoamFile buffer;
    FoamFileInfo info;
    std::size_t body_offset = 0; // where the body starts (for locating elements later)
    std::size_t body_line = 1;

    std::string name() const { return buffer.path().string(); }

    // A fresh tokenizer at the start of the body.
    FoamTokenizer body_tokenizer() const
    {
        FoamTokenizer tok(buffer.data().substr(body_offset), name(), body_line);
        return tok;
    }

    // ParseError at element `index` of the body's (first) list.
    ParseError element_error(ListKind kind, std::size_t index, const std::string& msg) const
    {
        FoamTokenizer tok = body_tokenizer();
        const ElementLocation at = locate_list_element(tok, info.header, kind, index);
        if (info.header.is_binary() && at.line != 0)
            return ParseError(name(), at.line,
                              "byte offset " + std::to_string(at.byte_offset + body_offset) + ": " +
                                  msg);
        return ParseError(name(), at.line, msg);
    }
};

OpenFile open_file(const fs::path& path, std::initializer_list<std::string_view> classes,
                   const std::string& object)
{
    OpenFile file(path);
    file.info.path = file.buffer.path();
    file.info.is_compressed = file.buffer.is_compressed();
    file.info.bytes = file.buffer.data().size();
    FoamTokenizer tok(file.buffer.data(), file.name());
    if (!has_header(tok))
    {
        const FoamToken& t = tok.peek();
        throw tok.error_at(t.line, "missing FoamFile header (found " + t.describe() + ")");
    }
    file.info.header = parse_header(tok);
    const FoamHeader& h = file.info.header;
    if (classes.size() > 0 &&
        std::find(classes.begin(), classes.end(), h.class_name) == classes.end())
    {
        std::string expected;
        for (std::string_view c : classes)
            expected += (expected.empty() ? "" : " or ") + std::string(c);
        throw ParseError(file.name(), h.line,
                         "wrong class '" + h.class_name + "' in FoamFile header, expected " +
                             expected);
    }
    if (!h.object.empty() && h.object != object)
        log::warning() << file.name() << ": FoamFile header says object '" << h.object
                       << "', expected '" << object << "'";
    // Body starts right after the header: skip to the next token so line counts are right.
    file.body_offset = tok.offset();
    file.body_line = tok.line();
    return file;
}

FoamTokenizer start_body(const OpenFile& file)
{
    return file.body_tokenizer();
}

// The line of the first word token `name` in a boundary/zones file (for messages).
std::size_t find_word_line(const OpenFile& file, const std::string& name)
{
    try
    {
        FoamTokenizer tok = file.body_tokenizer();
        for (FoamToken t = tok.next(); !t.is_end(); t = tok.next())
            if (t.is_word(name))
                return t.line;
    }
    catch (const Error&)
    {
    }
    return 0;
}

void read_points_into(const fs::path& path, PolyMesh& mesh, FoamFileInfo& info, bool parallel)
{
    OpenFile file = open_file(path, {"vectorField"}, "points");
    FoamTokenizer tok = start_body(file);
    ListReadOptions options;
    options.what = "points";
    options.parallel = parallel;
    mesh.points = read_vector_list(tok, file.info.header, options);
    expect_end_of_file(tok, "points");
    if (mesh.points.rows() > std::numeric_limits<Index>::max())
        throw ParseError(file.name(), 0, "too many points for the label size");
    for (Eigen::Index i = 0; i < mesh.points.rows(); ++i)
        if (!mesh.points.row(i).allFinite())
            throw file.element_error(ListKind::vector, static_cast<std::size_t>(i),
                                     "point " + std::to_string(i) + " has a non-finite coordinate");
    info = file.info;
}

void read_faces_into(const fs::path& path, PolyMesh& mesh, FoamFileInfo& info, bool parallel)
{
    OpenFile file = open_file(path, {"faceList", "faceCompactList"}, "faces");
    FoamTokenizer tok = start_body(file);
    ListReadOptions options;
    options.what = "faces";
    options.parallel = parallel;
    const bool compact = file.info.header.class_name == "faceCompactList";
    mesh.faces = read_face_list(tok, file.info.header, compact, options);
    expect_end_of_file(tok, "faces");

    // Vertex labels are checked against nPoints in check_face_points(), once the points
    // are read (after the topology, which keeps peak memory lower).
    const Index n_faces = mesh.faces.size();
    for (Index f = 0; f < n_faces; ++f)
    {
        const Index begin = mesh.faces.offsets[f];
        const Index end = mesh.faces.offsets[f + 1];
        if (end - begin < 3)
            throw file.element_error(
                compact ? ListKind::label : ListKind::face, static_cast<std::size_t>(f),
                "face " + std::to_string(f) + " has " + std::to_string(end - begin) +
                    " vertices, at least 3 are required");
    }
    info = file.info;
}

// Every vertex label in [0, nPoints). The faces file is opened again only to locate an
// offending label for the message.
void check_face_points(const PolyMesh& mesh, const FoamFileInfo& faces_info)
{
    const Index n_points = mesh.n_points();
    const std::vector<Index>& values = mesh.faces.values;
    std::size_t bad = values.size();
    for (std::size_t j = 0; j < values.size(); ++j)
        if (values[j] < 0 || values[j] >= n_points)
        {
            bad = j;
            break;
        }
    if (bad == values.size())
        return;
    const auto it = std::upper_bound(mesh.faces.offsets.begin(), mesh.faces.offsets.end(),
                                     static_cast<Index>(bad));
    const std::size_t f = static_cast<std::size_t>(it - mesh.faces.offsets.begin()) - 1;
    const std::string msg = "face " + std::to_string(f) + " has vertex label " +
                            std::to_string(values[bad]) + " outside [0, " +
                            std::to_string(n_points) + ") (nPoints from points)";
    const bool compact = faces_info.header.class_name == "faceCompactList";
    const OpenFile file = open_file(faces_info.path, {"faceList", "faceCompactList"}, "faces");
    if (compact)
        throw file.element_error(ListKind::face_compact_value, bad, msg);
    throw file.element_error(ListKind::face, f, msg);
}

void read_owner_into(const fs::path& path, PolyMesh& mesh, FoamFileInfo& info, bool parallel)
{
    OpenFile file = open_file(path, {"labelList"}, "owner");
    FoamTokenizer tok = start_body(file);
    ListReadOptions options;
    options.what = "owner";
    options.parallel = parallel;
    options.expected_size = static_cast<std::size_t>(mesh.n_faces());
    try
    {
        mesh.owner = read_label_list(tok, file.info.header, options);
    }
    catch (const ParseError& e)
    {
        // Make the size rule explicit: owner must have one entry per face.
        if (e.message().find("has size") != std::string::npos)
            throw ParseError(e.path(), e.line(),
                             e.message() + " (owner needs one entry per face; faces has " +
                                 std::to_string(mesh.n_faces()) + ")");
        throw;
    }
    expect_end_of_file(tok, "owner");
    for (std::size_t f = 0; f < mesh.owner.size(); ++f)
        if (mesh.owner[f] < 0)
            throw file.element_error(ListKind::label, f,
                                     "owner of face " + std::to_string(f) + " is negative (" +
                                         std::to_string(mesh.owner[f]) + ")");
    info = file.info;
}

void read_neighbour_into(const fs::path& path, PolyMesh& mesh, FoamFileInfo& info, bool parallel)
{
    OpenFile file = open_file(path, {"labelList"}, "neighbour");
    FoamTokenizer tok = start_body(file);
    ListReadOptions options;
    options.what = "neighbour";
    options.parallel = parallel;
    options.max_uniform_size = static_cast<std::size_t>(mesh.n_faces());
    mesh.neighbour = read_label_list(tok, file.info.header, options);
    expect_end_of_file(tok, "neighbour");
    const std::size_t n_faces = static_cast<std::size_t>(mesh.n_faces());
    if (mesh.neighbour.size() > n_faces)
        throw ParseError(file.name(), file.body_line,
                         "neighbour has " + std::to_string(mesh.neighbour.size()) +
                             " entries, more than the " + std::to_string(n_faces) + " faces");
    // Legacy files pad the boundary faces with -1: the internal faces end at the first -1.
    std::size_t n_internal = mesh.neighbour.size();
    if (mesh.neighbour.size() == n_faces)
    {
        const auto first_pad = std::find(mesh.neighbour.begin(), mesh.neighbour.end(), Index(-1));
        n_internal = static_cast<std::size_t>(first_pad - mesh.neighbour.begin());
        for (std::size_t f = n_internal; f < n_faces; ++f)
            if (mesh.neighbour[f] != -1)
                throw file.element_error(ListKind::label, f,
                                         "neighbour of face " + std::to_string(f) +
                                             " follows the -1 padding of a legacy neighbour "
                                             "list but is " +
                                             std::to_string(mesh.neighbour[f]));
    }
    for (std::size_t f = 0; f < n_internal; ++f)
    {
        const Index n = mesh.neighbour[f];
        if (n < 0)
            throw file.element_error(ListKind::label, f,
                                     "neighbour of face " + std::to_string(f) + " is negative (" +
                                         std::to_string(n) + ")");
        if (mesh.owner[f] >= n)
            throw file.element_error(ListKind::label, f,
                                     "internal face " + std::to_string(f) + " has owner " +
                                         std::to_string(mesh.owner[f]) + " >= neighbour " +
                                         std::to_string(n) + " (owner must be the lower cell)");
    }
    mesh.neighbour.resize(n_internal);
    mesh.neighbour.shrink_to_fit();
    info = file.info;
}

void read_boundary_into(const fs::path& path, PolyMesh& mesh, FoamFileInfo& info)
{
    OpenFile file = open_file(path, {"polyBoundaryMesh"}, "boundary");
    FoamTokenizer tok = start_body(file);
    mesh.patches = parse_boundary(tok);
    expect_end_of_file(tok, "boundary");
    Index expected_start = mesh.n_internal_faces();
    for (const Patch& p : mesh.patches)
    {
        if (p.start_face != expected_start)
            throw ParseError(file.name(), find_word_line(file, p.name),
                             "patch '" + p.name + "' has startFace " +
                                 std::to_string(p.start_face) + ", expected " +
                                 std::to_string(expected_start) +
                                 " (patches must follow each other from nInternalFaces " +
                                 std::to_string(mesh.n_internal_faces()) + ")");
        if (p.n_faces < 0 || p.n_faces > mesh.n_faces() - p.start_face)
            throw ParseError(file.name(), find_word_line(file, p.name),
                             "patch '" + p.name + "' has nFaces " + std::to_string(p.n_faces) +
                                 ", beyond the " + std::to_string(mesh.n_faces()) + " faces");
        expected_start = p.start_face + p.n_faces;
    }
    if (expected_start != mesh.n_faces())
        throw ParseError(file.name(), file.body_line,
                         "the patches end at face " + std::to_string(expected_start) +
                             " but the mesh has " + std::to_string(mesh.n_faces()) +
                             " faces (boundary faces not in any patch)");
    info = file.info;
}

void read_zones_into(const fs::path& path, std::vector<Zone>& zones,
                     std::optional<FoamFileInfo>& info, const std::string& object, Index max_label)
{
    if (!foam_file_exists(path))
        return;
    OpenFile file = open_file(path, {}, object);
    FoamTokenizer tok = start_body(file);
    zones = parse_zones(tok, file.info.header);
    expect_end_of_file(tok, object);
    for (const Zone& z : zones)
        for (Index l : z.labels)
            if (l < 0 || l >= max_label)
                throw ParseError(file.name(), find_word_line(file, z.name),
                                 "zone '" + z.name + "' has label " + std::to_string(l) +
                                     " outside [0, " + std::to_string(max_label) + ")");
    info = file.info;
}

// Topology first, then points (peak memory: the big faces text is gone before the points
// text arrives), then the checks that need both, then the zones.
void read_all(const fs::path& points_dir, const fs::path& faces_dir, FoamPolyMesh& result,
              const PolyMeshReadOptions& options)
{
    PolyMesh& mesh = result.mesh;
    read_faces_into(faces_dir / "faces", mesh, result.faces, options.parallel);
    read_owner_into(faces_dir / "owner", mesh, result.owner, options.parallel);
    read_neighbour_into(faces_dir / "neighbour", mesh, result.neighbour, options.parallel);
    read_boundary_into(faces_dir / "boundary", mesh, result.boundary);
    mesh.finalize();
    read_points_into(points_dir / "points", mesh, result.points, options.parallel);
    check_face_points(mesh, result.faces);
    if (options.read_zones)
    {
        read_zones_into(faces_dir / "pointZones", mesh.point_zones, result.point_zones,
                        "pointZones", mesh.n_points());
        read_zones_into(faces_dir / "faceZones", mesh.face_zones, result.face_zones, "faceZones",
                        mesh.n_faces());
        read_zones_into(faces_dir / "cellZones", mesh.cell_zones, result.cell_zones, "cellZones",
                        mesh.n_cells);
    }
    result.has_tet_base_pt_is = foam_file_exists(faces_dir / "tetBasePtIs");
}

} // namespace

std::size_t FoamPolyMesh::total_bytes() const
{
    std::size_t n = points.bytes + faces.bytes + owner.bytes + neighbour.bytes + boundary.bytes;
    for (const std::optional<FoamFileInfo>* z : {&point_zones, &face_zones, &cell_zones})
        if (*z)
            n += (*z)->bytes;
    return n;
}

Points read_points_file(const fs::path& path, FoamFileInfo* info, bool parallel)
{
    PolyMesh mesh;
    FoamFileInfo local;
    read_points_into(path, mesh, local, parallel);
    if (info)
        *info = std::move(local);
    return std::move(mesh.points);
}

FoamPolyMesh read_poly_mesh_dir(const fs::path& dir, const PolyMeshReadOptions& options)
{
    FoamPolyMesh result;
    result.points_dir = dir;
    result.faces_dir = dir;
    result.region = options.region;
    read_all(dir, dir, result, options);
    return result;
}

FoamPolyMesh read_poly_mesh(const fs::path& case_dir, const PolyMeshReadOptions& options)
{
    if (!fs::is_directory(case_dir))
        throw IoError("Case directory " + case_dir.string() + " does not exist");
    const std::vector<TimeDir> times = list_times(case_dir);
    FoamPolyMesh result;
    result.case_dir = case_dir;
    result.region = options.region;
    result.time = select_time(options.time.mode == TimeSelection::Mode::start
                                  ? start_times(case_dir, times, options.region)
                                  : times,
                              options.time);
    result.points_instance = find_instance(case_dir, times, result.time, "points", options.region);
    result.faces_instance = find_instance(case_dir, times, result.time, "faces", options.region);
    result.points_dir = poly_mesh_dir(case_dir, result.points_instance, options.region);
    result.faces_dir = poly_mesh_dir(case_dir, result.faces_instance, options.region);
    read_all(result.points_dir, result.faces_dir, result, options);
    return result;
}

std::vector<Index> read_label_list_file(const fs::path& path, const std::string& object)
{
    OpenFile file = open_file(path, {"labelList"}, object);
    FoamTokenizer tok = start_body(file);
    ListReadOptions options;
    options.what = object;
    std::vector<Index> labels = read_label_list(tok, file.info.header, options);
    expect_end_of_file(tok, object);
    for (std::size_t i = 0; i < labels.size(); ++i)
        if (labels[i] < 0)
            throw file.element_error(ListKind::label, i,
                                     object + " entry " + std::to_string(i) + " is negative (" +
                                         std::to_string(labels[i]) + ")");
    return labels;
}

} // namespace meshmorph::io
