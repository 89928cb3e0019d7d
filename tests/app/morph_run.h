// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Test helpers for the morphMesh application: run it in-process with the log
//! captured, and small file utilities.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "meshmorph/app/morph_mesh.h"
#include "meshmorph/core/log.h"

namespace meshmorph::test
{

struct MorphRun
{
    int code = -1;
    std::string out, err, log;
};

//! morphMesh with `args` (argv[0] added), its report, errors and log lines captured.
inline MorphRun run_morph_mesh(const std::vector<std::string>& args)
{
    std::vector<const char*> argv{"morphMesh"};
    for (const std::string& a : args)
        argv.push_back(a.c_str());
    std::ostringstream out, err;
    MorphRun r;
    {
        log::CaptureScope capture;
        r.code = app::run_morph_mesh(static_cast<int>(argv.size()), argv.data(), out, err);
        r.log = capture.text();
    }
    r.out = out.str();
    r.err = err.str();
    return r;
}

//! Writes `text` to `path`, creating its directory.
inline void write_text(const std::filesystem::path& path, const std::string& text)
{
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

} // namespace meshmorph::test
