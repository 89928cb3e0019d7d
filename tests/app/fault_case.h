// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Helpers of the fault tests (bad input, killed writes, resource limits): a small
//! real case (blockMesh's curved block, 12 cells) with a morphDict, the two applications
//! run as processes, and the check that a refused run left the case byte-identical.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "helpers.h"
#include "process_run.h"
#include "tree_snapshot.h"

namespace meshmorph::test
{

enum class App
{
    morph_mesh,
    check_mesh_quality
};

inline const char* app_name(App app)
{
    return app == App::morph_mesh ? "morphMesh" : "checkMeshQuality";
}

inline std::string read_file(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write_file(const std::filesystem::path& path, const std::string& bytes)
{
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
}

//! The morphDict of the base case: the outlet moves a little along x, the rest is fixed.
inline const char* const base_morph_dict =
    "method rbf;\nconflicts last;\n"
    "boundary\n{\n    outlet { type translate; vector (0.01 0 0); }\n}\n";

inline void write_morph_dict(const std::filesystem::path& dir, const std::string& body)
{
    write_file(dir / "system/morphDict",
               "FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }\n" +
                   body);
}

//! \brief A copy of tests/data/io/curved_block/<variant> (ascii, binary) under the test
//! work directory `faults/<name>`, with system/morphDict (`dict`).
inline std::filesystem::path make_fault_case(const std::string& name,
                                             const std::string& variant = "ascii",
                                             const std::string& dict = base_morph_dict)
{
    namespace fs = std::filesystem;
    const fs::path dir = scratch_dir("faults/" + name);
    fs::copy(data_path("io/curved_block/" + variant), dir, fs::copy_options::recursive);
    write_morph_dict(dir, dict);
    return dir;
}

//! The application `app` on the case `dir` with `extra` options, as a process.
inline ProcessRun run_app(App app, const std::filesystem::path& dir,
                          const std::vector<std::string>& extra = {},
                          const ProcessOptions& options = {})
{
    std::vector<std::string> argv{app == App::morph_mesh ? MESHMORPH_MORPH_MESH_EXE
                                                         : MESHMORPH_CHECK_MESH_QUALITY_EXE,
                                  "-case", dir.string()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return run_process(argv, options);
}

//! \brief Runs `app` on `dir` and expects exit `status`, an "Error: " on stderr holding
//! every string of `needles`, and the case byte-identical afterwards.
inline void expect_rejected(App app, const std::filesystem::path& dir, int status,
                            const std::vector<std::string>& needles,
                            const std::vector<std::string>& extra = {})
{
    SCOPED_TRACE(std::string(app_name(app)) + " on " + dir.string());
    const TreeSnapshot before = snapshot_tree(dir);
    const ProcessRun r = run_app(app, dir, extra);
    EXPECT_EQ(r.status, status) << r.out << r.err;
    EXPECT_NE(r.err.find("Error: "), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    for (const std::string& n : needles)
        EXPECT_NE(r.err.find(n), std::string::npos) << "'" << n << "' not in: " << r.err;
    EXPECT_EQ(tree_diff(before, snapshot_tree(dir)), "") << "the case must not change";
}

//! The 1-based line of the first occurrence of `text` in `file_text`.
inline int line_of(const std::string& file_text, const std::string& text)
{
    const std::size_t at = file_text.find(text);
    if (at == std::string::npos)
        return 0;
    return 1 + static_cast<int>(std::count(file_text.begin(), file_text.begin() + at, '\n'));
}

} // namespace meshmorph::test
