// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The morphMesh application as library functions: the case-level run (read, set up,
//! fit, evaluate, check, write: morph_case), its JSON document and the entry point. The morph
//! itself is the morph/ module (constraints.h, point_morph.h, morph_steps.h).
//!
//! Decisions (documented for users in `morphMesh -help` and tutorials/README.md):
//! - Exactness: rbf and idw interpolate every constraint (morph/point_morph.h); nothing is
//!   snapped after the evaluation.
//! - Steps: the motion is applied in refitted fractions, halved on new invalid cells
//!   (morph/morph_steps.h).
//! - Safety. A morph that creates negative-volume cells or wrongly oriented face pyramids
//!   (more than before) is refused: nothing is written unless `force`.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "meshmorph/app/exit_status.h"
#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/deform/space_deformation.h"
#include "meshmorph/io/case_instance.h"
#include "meshmorph/morph/constraints.h"
#include "meshmorph/morph/morph_steps.h"
#include "meshmorph/quality/check_mesh.h"

namespace meshmorph::app
{

//! Options of a morphMesh run (the command line).
struct MorphOptions
{
    std::filesystem::path case_dir = ".";
    //! morphDict; empty: <case>/system[/<region>]/morphDict; a relative path is relative to
    //! the case (OpenFOAM's -dict).
    std::filesystem::path dict;
    //! -region: the mesh constant/<region>/polyMesh, its dictionaries in system/<region>/,
    //! its fields and points in <time>/<region>/; "" for the default region.
    std::string region;
    io::TimeSelection time;
    bool overwrite = false;
    std::optional<std::string> method; //!< overrides the dictionary's `method`
    std::filesystem::path json;        //!< empty: no JSON
    bool vtk = false;                  //!< write a .vtu of the result
    std::filesystem::path vtk_file;    //!< -vtkFile; empty: VTK/morphMesh_[<region>_]<time>.vtu
    bool force = false;
    //! -parallel: morph the decomposed case (processor<rank>/), one rank per processor
    //! directory (the run must have started MPI: parallel::ParallelSession).
    bool parallel = false;
};

//! Wall-clock seconds per stage.
struct MorphTimings
{
    double read = 0, fit = 0, evaluate = 0, check = 0, untangle = 0, write = 0;
};

//! What a morphMesh run did.
struct MorphResult
{
    std::string method;
    std::string instance;           //!< instance the mesh was read from
    std::string region;             //!< -region ("" for the default region)
    std::string output_instance;    //!< instance written (or that would have been)
    morph::Constraints constraints; //!< the resolved constraint set (counts, conflicts)
    morph::PointMorph morph;
    QualityReport before, after;
    std::vector<morph::StepRecord> steps; //!< every step tried (morph_steps.h)
    double valid_fraction = 1.0;          //!< of the motion reached without new invalid cells
    double max_displacement = 0.0;        //!< the largest displacement of any point
    MorphTimings timings;
    bool parallel = false; //!< a -parallel run: before/after hold only the invalid cells
    bool refused = false;  //!< new invalid cells, nothing written (no force)
    std::string refusal;   //!< why
    bool written = false;
    std::filesystem::path points_file; //!< the written points file
    std::filesystem::path vtk_file;    //!< the written .vtu (if vtk)
};

//! \brief Run the whole morph in a case directory (see morphMesh -help).
//! Dictionary, mesh and surface errors throw before anything is written.
//! \throw ParseError, IoError, InvalidInput, SolverError.
MorphResult morph_case(const MorphOptions& options);

//! The `-json` document: method, constraints, centres, maxConstraintError, timings
//! {read, fit, evaluate, check, write}, before, after (the checker's keys), plus
//! relativeConstraintError, conflicts, handlePoints, slipPoints, outputInstance, written,
//! refused.
std::string morph_json(const MorphResult& result, int exit_status);

//! \brief The morphMesh application (argv[0] = program name): options, banner, morph_case,
//! summary. Report to `out`; the log, for the length of the run, to
//! log::stream_sink(out, err) (info on `out`, warnings and errors on `err`). Returns an exit
//! status; never throws.
int run_morph_mesh(int argc, const char* const argv[], std::ostream& out, std::ostream& err);

} // namespace meshmorph::app
