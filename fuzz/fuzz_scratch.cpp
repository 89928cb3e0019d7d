// SPDX-License-Identifier: GPL-3.0-or-later
// Scratch files for fuzz targets. /dev/shm keeps the file round trip of every input in memory.
#include "fuzz_scratch.h"

#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

#include "meshmorph/core/log.h"

namespace meshmorph::fuzz
{
namespace fs = std::filesystem;

namespace
{

fs::path make_scratch_dir()
{
    const char* tmpdir = std::getenv("TMPDIR");
    fs::path base = tmpdir && *tmpdir ? fs::path(tmpdir) : fs::path("/tmp");
    if (!tmpdir && fs::is_directory("/dev/shm"))
        base = "/dev/shm";
    std::string pattern = (base / "meshmorph-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
        throw std::runtime_error("cannot create a scratch directory under " + base.string());
    return pattern;
}

void remove_scratch_dir()
{
    std::error_code ec;
    fs::remove_all(scratch_dir(), ec);
}

} // namespace

const fs::path& scratch_dir()
{
    static const fs::path dir = make_scratch_dir();
    // Registered after `dir` is constructed, so it runs before `dir` is destroyed.
    static const bool registered = std::atexit(remove_scratch_dir) == 0;
    (void)registered;
    return dir;
}

fs::path write_scratch_file(const std::string& name, std::string_view data)
{
    const fs::path path = scratch_dir() / name;
    fs::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    if (!out.flush())
        throw std::runtime_error("cannot write " + path.string());
    return path;
}

void silence_log()
{
    log::set_sink([](log::Level, const std::string&) {});
}

} // namespace meshmorph::fuzz
