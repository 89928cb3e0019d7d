// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The morphMesh pipeline as library functions: fit a space deformation to the
//! constraints of morph_setup.h and move every mesh point (morph_points), and the whole
//! case-level run — read, set up, fit, evaluate, check, write (morph_case).
//!
//! Decisions (documented for users in `morphMesh -help` and tutorials/README.md):
//! - Exactness. The constrained points are not overwritten with their prescriptions after
//!   evaluation (that would hide a bad fit). The final fit includes every constraint; the
//!   residual max_i |d(x_i) - d_i| is measured on the evaluated field and reported. A direct
//!   RBF fit interpolates (residual at round-off, <= 1e-9 relative); greedy RBF stops at its
//!   tolerance; DM-FFD is least squares; FFD ignores constraints (its residual shows it).
//! - Slip. A first fit without the slip points gives d(x) there; its tangential part
//!   (projector of the slip planes) becomes their prescription in the final fit.
//! - 2D (empty patches). The fit uses the constraints of both empty planes (a well-posed 3D
//!   problem); every point is evaluated at its projection onto one empty plane and the
//!   normal component removed, so both planes move identically and stay planar.
//! - Safety. A morph that creates negative-volume cells or wrongly oriented face pyramids
//!   (more than before) is refused: nothing is written unless `force`.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "meshmorph/app/morph_setup.h"
#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/deform/space_deformation.h"
#include "meshmorph/io/case_instance.h"
#include "meshmorph/quality/check_mesh.h"

namespace meshmorph::app
{

//! Result of morph_points().
struct PointMorph
{
    Points displacement;              //!< nPoints x 3, d(x) for every mesh point
    Index n_constraints = 0;          //!< constraints of the final fit (slip points included)
    Index n_slip = 0;
    double max_prescribed = 0.0;      //!< max |prescribed displacement|
    //! max_i |displacement_i - prescribed_i| over the constrained points of the field returned
    //! (after snapping, if requested: then 0).
    double max_constraint_error = 0.0;
    double relative_constraint_error = 0.0; //!< divided by max(max_prescribed, 1e-12 diag)
    //! The fitted field's own residual max_i |d(x_i) - prescribed_i| before any snapping:
    //! round-off of an ill-conditioned direct solve, or the greedy tolerance.
    double max_fit_residual = 0.0;
    double relative_fit_residual = 0.0;
    bool snapped = false; //!< constrained points were set to their prescriptions
    FitReport report;                 //!< of the final fit
    double fit_seconds = 0.0;
    double evaluate_seconds = 0.0;
};

//! \brief Fit `deformation` to the constraints and evaluate it at every mesh point.
//! \param fit false: use the deformation as given (FFD with prescribed control points).
//! \param snap set the constrained points' displacements to their prescriptions after the
//! evaluation. For interpolating methods (RBF, greedy RBF) the fitted field misses them only
//! by its residual (round-off, or the greedy tolerance), so boundary points end exactly on
//! their target while the interior follows the smooth field; the residual is still reported
//! (max_fit_residual). Not for DM-FFD/FFD, whose residual is the method's least-squares error.
//! \throw InvalidInput if there are no constraints (and fit is true); SolverError.
PointMorph morph_points(const PolyMesh& mesh, const Constraints& constraints,
                        SpaceDeformation& deformation, bool fit = true, bool snap = false);

//! Options of a morphMesh run (the command line).
struct MorphOptions
{
    std::filesystem::path case_dir = ".";
    //! morphDict; empty: <case>/system/morphDict; a relative path is relative to the case
    //! (OpenFOAM's -dict).
    std::filesystem::path dict;
    io::TimeSelection time;
    bool overwrite = false;
    std::optional<std::string> method; //!< overrides the dictionary's `method`
    std::filesystem::path json;        //!< empty: no JSON
    bool vtk = false;
    bool force = false;
};

//! Wall-clock seconds per stage.
struct MorphTimings
{
    double read = 0, fit = 0, evaluate = 0, check = 0, write = 0;
};

//! What a morphMesh run did.
struct MorphResult
{
    std::string method;
    std::string instance;          //!< instance the mesh was read from
    std::string output_instance;   //!< instance written (or that would have been)
    Constraints constraints;       //!< the resolved constraint set (counts, conflicts)
    PointMorph morph;
    QualityReport before, after;
    MorphTimings timings;
    bool refused = false;          //!< new invalid cells, nothing written (no force)
    std::string refusal;           //!< why
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
std::string morph_json(const MorphResult& result);

//! Exit statuses of morphMesh (listed by -help).
inline constexpr int exit_morph_ok = 0;
inline constexpr int exit_morph_input_error = 2;  //!< options, dictionary, mesh, surface files
inline constexpr int exit_morph_refused = 3;      //!< new invalid cells; nothing written
inline constexpr int exit_morph_solver_error = 4; //!< the fit failed
inline constexpr int exit_morph_internal_error = 5;

//! \brief The morphMesh application (argv[0] = program name): options, banner, morph_case,
//! summary. Report to `out`, errors to `err`. Returns an exit status; never throws.
int run_morph_mesh(int argc, const char* const argv[], std::ostream& out, std::ostream& err);

} // namespace meshmorph::app
