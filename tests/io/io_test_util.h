// SPDX-License-Identifier: GPL-3.0-or-later
// Small helpers shared by the polyMesh I/O tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_file.h"

namespace meshmorph::test
{

//! Raw bytes of a file (no decompression).
inline std::string file_bytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in.good()) << "cannot open " << path;
    std::ostringstream os;
    os << in.rdbuf();
    return os.str();
}

//! Decompressed contents of `path` or `path.gz`.
inline std::string file_text(const std::filesystem::path& path)
{
    return io::read_foam_file(path).data;
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes)
{
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

//! Copy a directory tree (replacing the target).
inline void copy_tree(const std::filesystem::path& from, const std::filesystem::path& to)
{
    std::filesystem::remove_all(to);
    std::filesystem::create_directories(to.parent_path());
    std::filesystem::copy(from, to, std::filesystem::copy_options::recursive);
}

//! Runs f and returns the what() of the meshmorph::Error it throws (fails if none).
template <class F> std::string error_of(F f)
{
    try
    {
        f();
    }
    catch (const Error& e)
    {
        return e.what();
    }
    ADD_FAILURE() << "no meshmorph::Error was thrown";
    return {};
}

//! Runs a shell command in `dir` with output to `log`; returns its exit status.
inline int run_in(const std::filesystem::path& dir, const std::string& command,
                  const std::string& log = "log.run")
{
    const std::string cmd =
        "cd '" + dir.string() + "' && " + command + " > '" + log + "' 2>&1 < /dev/null";
    return std::system(cmd.c_str());
}

} // namespace meshmorph::test
