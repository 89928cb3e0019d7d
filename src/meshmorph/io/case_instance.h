// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Time directories of a case and the instances (directories) a polyMesh is read from.
//!
//! docs/polymesh-format.md §1: when reading at time t, `points` come from the newest time
//! directory <= t whose `polyMesh/` holds `points` (else `constant`); `faces`, `owner`,
//! `neighbour` and `boundary` are looked up the same way keyed on `faces`.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace meshmorph::io
{

//! One time directory of a case.
struct TimeDir
{
    std::string name; //!< directory name as written, e.g. "0", "0.005", "1e-05"
    double value = 0; //!< its numeric value
};

//! \brief The time directories of `case_dir`, sorted by value: every sub-directory whose
//! whole name parses as a finite number (`constant`, `system`, `0.orig` are not times).
//! An absent or unreadable case directory gives an empty list.
std::vector<TimeDir> list_times(const std::filesystem::path& case_dir);

//! Which time to read, as OpenFOAM utilities select it.
struct TimeSelection
{
    enum class Mode
    {
        first, //!< the earliest time directory (the usual startTime), or constant if none
        //! The mesh a case starts from: the earliest time directory that is not a motion
        //! result (motion_results), or constant if none. morphMesh's default: a re-run
        //! reads what the first run read, never its result.
        start,
        latest, //!< `-latestTime`: the newest time directory, or constant if none
        time,   //!< `-time T`: the time directory named or valued T; "constant" is allowed
    };
    Mode mode = Mode::first;
    std::string time; //!< for Mode::time

    static TimeSelection first_time() { return {}; }
    static TimeSelection start_time() { return {Mode::start, {}}; }
    static TimeSelection latest_time() { return {Mode::latest, {}}; }
    static TimeSelection at(std::string t) { return {Mode::time, std::move(t)}; }
};

//! \brief Whether time directory `time` of the case holds a motion result: moved points
//! (`polyMesh/points`) without a mesh of its own (no `faces`), as morphMesh, moveMesh, a
//! moving-mesh solver and reconstructPar of those write. snappyHexMesh without -overwrite
//! writes whole meshes, which are not motion results.
bool is_motion_result(const std::filesystem::path& case_dir, const std::string& time,
                      const std::string& region = "");

//! \brief `times` without the motion results (is_motion_result): the times a mesh can
//! start from, against which TimeSelection::start and its next time are resolved.
std::vector<TimeDir> start_times(const std::filesystem::path& case_dir,
                                 const std::vector<TimeDir>& times, const std::string& region = "");

//! \brief Resolve a selection against `times` (as list_times returns them). Returns the
//! selected time's name, or "constant" when there are no times (or `-time constant`).
//! `-time T` matches a directory name exactly or, failing that, a value within a relative
//! 1e-9 (time names are printed with limited precision, so "0.1" must find 0.1000000001).
//! Mode::start resolves like Mode::first: pass it start_times.
//! \throw InvalidInput if `-time T` names no existing time or T is not a number.
std::string select_time(const std::vector<TimeDir>& times, const TimeSelection& selection);

//! \brief The polyMesh directory of `instance` ("constant" or a time name) and `region`
//! ("" or "region0" for the default region): `<case>/<instance>[/<region>]/polyMesh`.
std::filesystem::path poly_mesh_dir(const std::filesystem::path& case_dir,
                                    const std::string& instance, const std::string& region = "");

//! \brief The instance holding polyMesh file `key` ("points" or "faces", plain or .gz) for
//! reading at `time` ("constant" or a time name from `times`): the newest time directory
//! with value <= time whose polyMesh has the file, else "constant". Times are compared by
//! value with a relative tolerance of 1e-9 (see select_time).
//! \throw IoError if not even `constant` holds the file.
std::string find_instance(const std::filesystem::path& case_dir, const std::vector<TimeDir>& times,
                          const std::string& time, const std::string& key,
                          const std::string& region = "");

//! How time names are printed (controlDict `timeFormat`).
enum class TimeFormat
{
    general,    //!< like printf %g (OpenFOAM's default)
    fixed,      //!< like printf %f
    scientific, //!< like printf %e
};

//! \brief Format a time value as OpenFOAM names its directories: C++ stream formatting with
//! `precision` (controlDict `timePrecision`, default 6) in the given format, e.g. 1 -> "1",
//! 0.005 -> "0.005", 1e-05 -> "1e-05".
std::string format_time_name(double value, TimeFormat format = TimeFormat::general,
                             int precision = 6);

//! The time-naming settings of `system/controlDict`.
struct TimeSettings
{
    double delta_t = 1;
    TimeFormat format = TimeFormat::general;
    int precision = 6;
};

//! \brief Read `deltaT`, `timeFormat` and `timePrecision` from `<case>/system/controlDict`
//! (defaults 1, general, 6 for absent entries or an absent controlDict).
//! \throw ParseError on a malformed controlDict or a bad value.
TimeSettings read_time_settings(const std::filesystem::path& case_dir);

//! \brief Name of the time directory after `time` ("constant" counts as the earliest time of
//! the case, or 0): time + deltaT formatted per `settings`. If that name equals the current
//! one (precision too low), the precision is raised until it differs, as OpenFOAM does.
std::string next_time_name(const std::vector<TimeDir>& times, const std::string& time,
                           const TimeSettings& settings);

//! The file `-vtk` writes: `<case>/VTK/<app_name>_[<region>_]<time>.vtu` (foamToVTK's folder).
std::filesystem::path default_vtk_file(const std::filesystem::path& case_dir,
                                       const std::string& app_name, const std::string& region,
                                       const std::string& time);

} // namespace meshmorph::io
