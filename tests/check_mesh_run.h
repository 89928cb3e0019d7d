// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Test helper: run the checkMeshQuality application in-process and keep what it
//! printed.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "meshmorph/app/check_mesh_case.h"

namespace meshmorph::test
{

struct AppRun
{
    int status;
    std::string out, err;
};

//! checkMeshQuality with `args` (argv[0] added).
inline AppRun run_check_mesh_quality(std::vector<std::string> args)
{
    args.insert(args.begin(), "checkMeshQuality");
    std::vector<const char*> argv;
    for (const std::string& a : args)
        argv.push_back(a.c_str());
    std::ostringstream out, err;
    const int status =
        app::run_check_mesh_quality(static_cast<int>(argv.size()), argv.data(), out, err);
    return {status, out.str(), err.str()};
}

} // namespace meshmorph::test
