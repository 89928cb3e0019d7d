// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Real OpenFOAM cases for oracle tests, generated on demand by scripts/openfoam/*.sh
//! with the installed OpenFOAM and cached under MESHMORPH_TEST_WORK_DIR/openfoam/<name>
//! (header-only).
//!
//! Usage in a test:
//! \code
//!   if (!test::openfoam_available()) GTEST_SKIP() << "OpenFOAM not installed: <what>";
//!   const std::filesystem::path case_dir = test::openfoam_case("curved-block");
//!   // case_dir/constant/polyMesh/{points,faces,owner,neighbour,boundary}, case_dir/log.*
//! \endcode
//!
//! ctest runs test processes in parallel: each case is generated once, under an exclusive
//! flock(2) on <work>/openfoam/<name>.lock, into <name>, and marked complete by <name>/.done.
//! Other processes block on the lock, then reuse the case. A case without .done (an
//! interrupted run) or older than any script in scripts/openfoam/ is generated again.
//! Never modify a returned case in place: copy it (e.g. to test::scratch_dir) first.
#pragma once

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "helpers.h"

namespace meshmorph::test
{

namespace detail
{

//! A shell word: 'text' with embedded single quotes escaped.
inline std::string shell_quote(const std::string& text)
{
    std::string quoted = "'";
    for (const char c : text)
    {
        if (c == '\'')
            quoted += "'\\''";
        else
            quoted += c;
    }
    return quoted + "'";
}

inline std::filesystem::path openfoam_scripts_dir()
{
    return std::filesystem::path(MESHMORPH_SOURCE_DIR) / "scripts" / "openfoam";
}

//! Newest modification time of the generator scripts (a cached case older than this is stale).
inline std::filesystem::file_time_type newest_script_time()
{
    std::filesystem::file_time_type newest = std::filesystem::file_time_type::min();
    for (const auto& entry : std::filesystem::directory_iterator(openfoam_scripts_dir()))
        if (entry.is_regular_file() && entry.last_write_time() > newest)
            newest = entry.last_write_time();
    return newest;
}

//! Last lines of a text file, for error messages.
inline std::string tail_of(const std::filesystem::path& path, std::size_t n_lines)
{
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    std::string tail;
    for (std::size_t i = lines.size() > n_lines ? lines.size() - n_lines : 0; i < lines.size(); ++i)
        tail += "    " + lines[i] + "\n";
    return tail;
}

//! Holds an exclusive flock(2) on a file for its lifetime.
class FileLock
{
public:
    explicit FileLock(const std::filesystem::path& path)
        : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644))
    {
        if (fd_ < 0)
            throw std::runtime_error("cannot open lock file " + path.string());
        while (::flock(fd_, LOCK_EX) != 0)
        {
            if (errno != EINTR)
            {
                ::close(fd_);
                throw std::runtime_error("cannot lock " + path.string());
            }
        }
    }
    ~FileLock()
    {
        ::flock(fd_, LOCK_UN);
        ::close(fd_);
    }
    FileLock(const FileLock&) = delete;
    FileLock& operator=(const FileLock&) = delete;

private:
    int fd_;
};

//! Format variants: a name ending in one of these is <base> converted by convert-format.sh.
inline const std::vector<std::pair<std::string, std::string>>& format_suffixes()
{
    static const std::vector<std::pair<std::string, std::string>> suffixes{
        {"-binary-gz", "binary compressed"},
        {"-ascii-gz", "ascii compressed"},
        {"-binary", "binary"},
        {"-ascii", "ascii"}};
    return suffixes;
}

} // namespace detail

//! Names openfoam_case() knows (format variants aside), with the script that makes each.
inline const std::map<std::string, std::string>& openfoam_case_scripts()
{
    static const std::map<std::string, std::string> scripts{
        {"curved-block", "curved-block.sh {dir}"},         // 336 hex cells, arc/spline edges
        {"tet-gmsh", "tet-gmsh.sh {dir}"},                 // ~900 tetrahedra (gmsh + gmshToFoam)
        {"flange", "flange.sh {dir}"},                     // snappyHexMesh flange, ~19k cells
        {"damaged", "damaged.sh {curved-block} {dir}"},    // curved-block, inverted + twisted
        {"motorbike-coarse", "motorbike.sh {dir} coarse"}, // ~14k cells, < 10 s
        {"motorbike", "motorbike.sh {dir}"},               // full tutorial, ~353k cells, minutes
        {"wedge-block", "wedge-block.sh {dir}"},           // 50 cells, wedges about z
        {"wedge-twisted", "wedge-block.sh {dir} twisted"}, // the same, edges across leaning
        // Wedge tutorials: 1900 cells about x; 3466 cells about z.
        {"wedge-cone", "blockmesh-tutorial.sh {dir} incompressible/pimpleFoam/laminar/movingCone"},
        {"wedge-dlr", "blockmesh-tutorial.sh {dir} combustion/reactingFoam/RAS/DLR_A_LTS"},
        // Converted tutorials: biconic25-55Run35, a 0.1 degree wedge about x (32385 cells);
        // nacaAirfoil, a 2D STAR-CD mesh with empty planes normal to z.
        {"biconic", "converted-tutorial.sh {dir} biconic"},
        {"naca-airfoil", "converted-tutorial.sh {dir} naca"},
        // rivuletPanel's blockMesh (43200 cells): a film panel one cell thick at its walls.
        {"rivulet-panel", "blockmesh-tutorial.sh {dir} lagrangian/reactingParcelFoam/rivuletPanel"},
        // Cyclic tutorials: 4096 cells periodic in x, y, z; an 80-cell periodic column.
        {"cyclic-box", "blockmesh-tutorial.sh {dir} DNS/dnsFoam/boxTurb16"},
        {"cyclic-column",
         "blockmesh-tutorial.sh {dir} incompressible/boundaryFoam/boundaryWallFunctions"},
        // 1D periodic: 40 graded cells in one column, cyclic left/right, empty front/back.
        {"periodic-1d",
         "blockmesh-tutorial.sh {dir} incompressible/pimpleFoam/laminar/planarPoiseuille"},
        // AMI: 3072 cells (m4), a rotor and a stator region joined only by a cyclicAMI pair.
        {"ami-mixer",
         "blockmesh-tutorial.sh {dir} incompressible/pimpleFoam/laminar/mixerVesselAMI2D"},
        // Split regions: 3000 cells split by cellZones into 5 region meshes (80 to 1200 cells),
        // each keeping every cellZone, the other regions' empty.
        {"split-heater",
         "split-regions.sh {dir} heatTransfer/chtMultiRegionFoam/multiRegionHeater"},
    };
    return scripts;
}

//! \brief Path of the named OpenFOAM case, generating it first if needed (see file comment).
//! \param name one of openfoam_case_scripts(), optionally followed by a format suffix
//!   `-binary`, `-ascii`, `-binary-gz` or `-ascii-gz` (that case converted by
//!   convert-format.sh: binary and/or gzipped polyMesh files), e.g. "flange-binary-gz".
//! \pre openfoam_available() (tests check it and skip first).
//! \throw std::runtime_error for an unknown name, or when generation fails: the message
//!   names the command and shows the end of its log (<work>/openfoam/<name>.log).
inline std::filesystem::path openfoam_case(const std::string& name)
{
    namespace fs = std::filesystem;
    std::string command;
    for (const auto& [suffix, format] : detail::format_suffixes())
    {
        if (name.size() > suffix.size() &&
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        {
            const std::string base = name.substr(0, name.size() - suffix.size());
            command = "convert-format.sh " + detail::shell_quote(openfoam_case(base).string()) +
                      " {dir} " + format;
            break;
        }
    }
    if (command.empty())
    {
        const auto found = openfoam_case_scripts().find(name);
        if (found == openfoam_case_scripts().end())
            throw std::runtime_error("openfoam_case: unknown case '" + name +
                                     "' (see tests/openfoam_cases.h)");
        command = found->second;
        const std::string dependency = "{curved-block}";
        if (const auto at = command.find(dependency); at != std::string::npos)
            command.replace(at, dependency.size(),
                            detail::shell_quote(openfoam_case("curved-block").string()));
    }
    if (!openfoam_available())
        throw std::runtime_error("openfoam_case('" + name +
                                 "'): OpenFOAM not installed (check openfoam_available() first)");

    const fs::path root = fs::path(MESHMORPH_TEST_WORK_DIR) / "openfoam";
    fs::create_directories(root);
    const fs::path dir = root / name;
    const fs::path done = dir / ".done";
    const fs::path log = root / (name + ".log");

    const detail::FileLock lock(root / (name + ".lock"));
    if (fs::exists(done) && fs::last_write_time(done) >= detail::newest_script_time())
        return dir;

    fs::remove_all(dir);
    const std::string placeholder = "{dir}";
    command.replace(command.find(placeholder), placeholder.size(),
                    detail::shell_quote(dir.string()));
    const std::string shell = "bash " +
                              detail::shell_quote((detail::openfoam_scripts_dir() / "").string()) +
                              command + " > " + detail::shell_quote(log.string()) + " 2>&1";
    if (std::system(shell.c_str()) != 0 || !fs::exists(dir / "constant" / "polyMesh"))
        throw std::runtime_error("openfoam_case('" + name + "') failed: " + shell + "\n  end of " +
                                 log.string() + ":\n" + detail::tail_of(log, 15));
    std::ofstream(done) << command << '\n';
    return dir;
}

} // namespace meshmorph::test
