// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A scratch directory for fuzz targets whose readers take a path: each input is
//! written to a file there before it is read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace meshmorph::fuzz
{

//! \brief This process's scratch directory (created on first use under $TMPDIR, or /dev/shm
//! when it exists, and removed at exit), so parallel fuzzers never share files.
const std::filesystem::path& scratch_dir();

//! \brief Write `data` to scratch_dir()/name (parent directories created), replacing it, and
//! return the path.
std::filesystem::path write_scratch_file(const std::string& name, std::string_view data);

//! The fuzzer's bytes as a string_view.
inline std::string_view as_text(const std::uint8_t* data, std::size_t size)
{
    return {reinterpret_cast<const char*>(data), size};
}

//! Drop log output (warnings about odd input), which would flood the fuzzer's console.
void silence_log();

} // namespace meshmorph::fuzz
