// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: a pointVectorField file (io/point_field), read for a valid mesh with
// patches of several kinds (tests/data/io/point_field/ascii: inlet, outlet, walls of type
// wall, frontAndBack), then its patch values applied to the points.
#include <cstddef>
#include <cstdint>
#include <optional>

#include "fuzz_scratch.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/point_field.h"
#include "meshmorph/io/read_poly_mesh.h"

namespace
{

using namespace meshmorph;
namespace fs = std::filesystem;

std::optional<PolyMesh> mesh;

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    fuzz::silence_log();
    const fs::path dir = fs::path(MESHMORPH_TEST_DATA_DIR) / "io" / "point_field" / "ascii" /
                         "constant" / "polyMesh";
    mesh = io::read_poly_mesh_dir(dir).mesh;
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const fs::path path = fuzz::write_scratch_file("pointDisplacement", fuzz::as_text(data, size));
    try
    {
        const io::PointVectorField field = io::read_point_vector_field(path, *mesh);
        (void)io::apply_patch_values(field, *mesh);
    }
    catch (const Error&)
    {
    }
    return 0;
}
