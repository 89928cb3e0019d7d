// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The checkMeshQuality application as a library function, plus its case-level pieces:
//! meshQualityDict and controlDict settings, OpenFOAM set files, the VTK quality fields.
//!
//! applications/checkMeshQuality/main.cpp only calls run_check_mesh_quality(), so every
//! behaviour (options, exit codes, files written) is testable in-process.
#pragma once

#include "meshmorph/app/exit_status.h"
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "meshmorph/quality/check_mesh.h"

namespace meshmorph::app
{

//! \brief The meshQualityDict criteria (spec §5) of `path` (usually system/meshQualityDict).
//! Keys are looked up with regex matching; all are mandatory except minFaceFlatness.
//! `#includeEtc "X"` is resolved against $WM_PROJECT_DIR/etc (or /usr/share/openfoam/etc).
//! \throw IoError if the file is missing; ParseError naming file and line for a missing
//! key or a bad value.
MeshQualitySettings read_mesh_quality_dict(const std::filesystem::path& path);

//! \brief `writePrecision` of `<case>/system/controlDict` (6 when absent).
//! \throw ParseError on a malformed controlDict or a non-integer value.
int read_write_precision(const std::filesystem::path& case_dir);

//! \brief An OpenFOAM faceSet / cellSet / pointSet file (ascii, `class faceSet`, a labelList
//! body) that OpenFOAM's tools (foamToVTK -faceSet, setsToZones) read.
//! \param location the header's `location`, e.g. "constant/polyMesh/sets".
std::string mesh_set_file_text(const MeshSet& set, const std::string& location);

//! \brief Write every set to `<case>/<instance>[/<region>]/polyMesh/sets/<name>`
//! atomically. Returns the paths written. \throw IoError naming the path on failure.
std::vector<std::filesystem::path> write_mesh_sets(const std::vector<MeshSet>& sets,
                                                   const std::filesystem::path& case_dir,
                                                   const std::string& instance,
                                                   const std::string& region = "");

//! \brief checkMesh's cellToRegion file: an OpenFOAM labelList (ascii, `class labelList`) of
//! each cell's region, as OpenFOAM's List writes it (one label a line; on one line, `N(...)`,
//! up to 10 labels). \param location the header's `location`, e.g. "constant".
std::string cell_to_region_file_text(const std::vector<Index>& cell_to_region,
                                     const std::string& location);

//! \brief Write `<case>/<time>[/<region>]/cellToRegion` atomically (where checkMesh writes it).
//! Returns the path. \throw IoError naming the path on failure.
std::filesystem::path write_cell_to_region(const std::vector<Index>& cell_to_region,
                                           const std::filesystem::path& case_dir,
                                           const std::string& time, const std::string& region = "");

//! \brief Run checkMeshQuality with argv (argv[0] = program name); the report goes to `out`,
//! and the log, for the length of the run, to log::stream_sink(out, err) (info on `out`,
//! warnings and errors on `err`). Returns the exit status (exit_ok, exit_checks_failed,
//! exit_input_error, exit_internal_error); never throws.
int run_check_mesh_quality(int argc, const char* const argv[], std::ostream& out,
                           std::ostream& err);

} // namespace meshmorph::app
