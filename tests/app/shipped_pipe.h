// SPDX-License-Identifier: GPL-3.0-or-later
//! The tutorial pipe's mesh as shipped, for tests that build their cases from it.
#pragma once

#include <filesystem>

#include "meshmorph/io/read_poly_mesh.h"

namespace meshmorph::test
{

inline std::filesystem::path pipe_tutorial_dir()
{
    return std::filesystem::path(MESHMORPH_SOURCE_DIR) / "tutorials/pipe";
}

//! tutorials/pipe/constant/polyMesh. Read from `constant` by name: after the README's
//! `scripts/run-pipe.sh` the tutorial also holds its morphed mesh in `1/`, which the default
//! time selection (the earliest time directory) would read instead, so a test's premise
//! would depend on what was run in the source tree before it.
inline io::FoamPolyMesh read_shipped_pipe()
{
    io::PolyMeshReadOptions o;
    o.time = io::TimeSelection::at("constant");
    return io::read_poly_mesh(pipe_tutorial_dir(), o);
}

} // namespace meshmorph::test
