// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the STL (ascii and binary) or OBJ reader (io/surface_io), chosen by the
// scratch file's extension MESHMORPH_FUZZ_SURFACE_EXT (".stl" or ".obj").
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_scratch.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/surface_io.h"

#ifndef MESHMORPH_FUZZ_SURFACE_EXT
#error "define MESHMORPH_FUZZ_SURFACE_EXT as .stl or .obj"
#endif

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    meshmorph::fuzz::silence_log();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::filesystem::path path = meshmorph::fuzz::write_scratch_file(
        std::string("surface") + MESHMORPH_FUZZ_SURFACE_EXT, meshmorph::fuzz::as_text(data, size));
    try
    {
        (void)meshmorph::io::read_surface(path);
    }
    catch (const meshmorph::Error&)
    {
    }
    return 0;
}
