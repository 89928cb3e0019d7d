// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: one polyMesh file of any kind, chosen by its FoamFile class as the reader
// would (vectorField: points; faceList/faceCompactList: faces; labelList: owner or neighbour
// by `object`; polyBoundaryMesh: boundary; regIOobject: zones), ascii or binary as the header
// says, plain or gzip. The body is parsed in memory first (fast, where most inputs fail); an
// input that parses is then read by read_poly_mesh_dir in place of its file in a valid mesh
// (tests/data/io/curved_block/ascii), so that the checks across files run too.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "fuzz_scratch.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/boundary_io.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/foam_lists.h"
#include "meshmorph/io/read_poly_mesh.h"

namespace
{

using namespace meshmorph;
using namespace meshmorph::io;
namespace fs = std::filesystem;

const char* const mesh_files[] = {"points",   "faces",     "owner",     "neighbour",
                                  "boundary", "faceZones", "cellZones", "pointZones"};
std::map<std::string, std::string> fixture; // file name -> contents of the valid mesh

// The polyMesh file an input stands for, or "" when its class is none of them.
std::string file_of(const FoamHeader& h)
{
    if (h.class_name == "vectorField")
        return "points";
    if (h.class_name == "faceList" || h.class_name == "faceCompactList")
        return "faces";
    if (h.class_name == "labelList")
        return h.object == "neighbour" ? "neighbour" : "owner";
    if (h.class_name == "polyBoundaryMesh")
        return "boundary";
    if (h.class_name == "regIOobject" &&
        (h.object == "faceZones" || h.object == "cellZones" || h.object == "pointZones"))
        return h.object;
    return "";
}

// Parses the body as the reader of `file` does; walks to an element as error messages do.
void parse_body(FoamTokenizer tok, const FoamHeader& h, const std::string& file)
{
    const FoamTokenizer start = tok;
    ListReadOptions options;
    options.what = file;
    options.parallel = false;
    std::size_t n = 0;
    ListKind kind = ListKind::label;
    if (file == "points")
    {
        n = static_cast<std::size_t>(read_vector_list(tok, h, options).rows());
        kind = ListKind::vector;
    }
    else if (file == "faces")
    {
        const bool compact = h.class_name == "faceCompactList";
        const CompactList faces = read_face_list(tok, h, compact, options);
        n = compact ? faces.values.size() : static_cast<std::size_t>(faces.size());
        kind = compact ? ListKind::face_compact_value : ListKind::face;
    }
    else if (file == "owner" || file == "neighbour")
        n = read_label_list(tok, h, options).size();
    else if (file == "boundary")
        (void)parse_boundary(tok);
    else
        (void)parse_zones(tok, h);
    expect_end_of_file(tok, file);
    if (file == "boundary" || file.ends_with("Zones"))
        return;
    for (const std::size_t index : {n / 2, n})
    {
        FoamTokenizer walker = start;
        (void)locate_list_element(walker, h, kind, index);
    }
}

// The whole mesh with `data` as `file`; the valid file is put back afterwards.
void read_mesh_with(const std::string& file, std::string_view data)
{
    fuzz::write_scratch_file("polyMesh/" + file, data);
    PolyMeshReadOptions options;
    options.parallel = false;
    try
    {
        (void)read_poly_mesh_dir(fuzz::scratch_dir() / "polyMesh", options);
    }
    catch (const Error&)
    {
    }
    fuzz::write_scratch_file("polyMesh/" + file, fixture[file]);
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    fuzz::silence_log();
    const fs::path dir = fs::path(MESHMORPH_TEST_DATA_DIR) / "io" / "curved_block" / "ascii" /
                         "constant" / "polyMesh";
    for (const char* name : mesh_files)
    {
        fixture[name] = read_foam_file(dir / name).data;
        fuzz::write_scratch_file(std::string("polyMesh/") + name, fixture[name]);
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string_view raw = fuzz::as_text(data, size);
    std::string file;
    try
    {
        const std::string text = is_gzip(raw) ? gzip_decompress(raw, "fuzz") : std::string(raw);
        FoamTokenizer tok(text, "constant/polyMesh/fuzz");
        if (!has_header(tok))
            return 0;
        const FoamHeader header = parse_header(tok);
        file = file_of(header);
        if (file.empty())
            return 0;
        parse_body(tok, header, file);
    }
    catch (const Error&)
    {
        return 0;
    }
    read_mesh_with(file, raw);
    return 0;
}
