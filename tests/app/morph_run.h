// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Test helpers for the morphMesh application: run it in-process with its output
//! captured, and small file utilities.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "meshmorph/app/morph_mesh.h"

namespace meshmorph::test
{

struct MorphRun
{
    int code = -1;
    std::string out; //!< stdout: report and info lines
    std::string err; //!< stderr: "Warning: ..." and "Error: ..." lines
    std::string log; //!< out then err, for searching a line wherever it went
};

//! morphMesh with `args` (argv[0] added). The application logs to the streams it is given,
//! so `out` and `err` hold everything it printed.
inline MorphRun run_morph_mesh(const std::vector<std::string>& args)
{
    std::vector<const char*> argv{"morphMesh"};
    for (const std::string& a : args)
        argv.push_back(a.c_str());
    std::ostringstream out, err;
    MorphRun r;
    r.code = app::run_morph_mesh(static_cast<int>(argv.size()), argv.data(), out, err);
    r.out = out.str();
    r.err = err.str();
    r.log = r.out + r.err;
    return r;
}

//! Writes `text` to `path`, creating its directory.
inline void write_text(const std::filesystem::path& path, const std::string& text)
{
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

} // namespace meshmorph::test
