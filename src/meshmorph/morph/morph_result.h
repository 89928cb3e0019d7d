// SPDX-License-Identifier: GPL-3.0-or-later
//! \file What a morph of a case is asked to do (MorphOptions) and what it did (MorphResult,
//! MorphTimings): plain records, read by the pipeline's stages and by the reports.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/io/case_instance.h"
#include "meshmorph/morph/constraint_set.h"
#include "meshmorph/morph/folded_faces.h"
#include "meshmorph/morph/invalid_cells_location.h"
#include "meshmorph/morph/morph_steps.h"
#include "meshmorph/morph/point_morph.h"
#include "meshmorph/quality/quality_report.h"
#include "meshmorph/quality/symmetry_plane_planarity.h"

namespace meshmorph::morph
{

//! Options of a morphMesh run (the command line of morphMesh).
struct MorphOptions
{
    std::filesystem::path case_dir = ".";
    //! morphDict; empty: <case>/system[/<region>]/morphDict; a relative path is relative to
    //! the case (OpenFOAM's -dict).
    std::filesystem::path dict;
    //! -region: the mesh constant/<region>/polyMesh, its dictionaries in system/<region>/,
    //! its fields and points in <time>/<region>/; "" for the default region.
    std::string region;
    //! Which mesh to morph; by default the one the case starts from (TimeSelection::start):
    //! the same run twice reads the same mesh, never the first run's result.
    io::TimeSelection time = io::TimeSelection::start_time();
    bool overwrite = false;
    std::optional<std::string> method; //!< overrides the dictionary's `method`
    //! Compute the per-cell scaled Jacobian before and after (not a checkMesh check: for a
    //! JSON or VTK report; it costs as much as the checks themselves).
    bool scaled_jacobian = false;
    bool vtk = false;               //!< write a .vtu of the result
    std::filesystem::path vtk_file; //!< -vtkFile; empty: VTK/morphMesh_[<region>_]<time>.vtu
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
    std::string instance;        //!< instance the mesh was read from
    std::string region;          //!< -region ("" for the default region)
    std::string output_instance; //!< instance written (or that would have been)
    Constraints constraints;     //!< the resolved constraint set (counts, conflicts)
    PointMorph morph;
    QualityReport before, after;
    std::vector<StepRecord> steps; //!< every step tried (morph_steps.h)
    double valid_fraction = 1.0;   //!< of the motion reached without new invalid cells
    double max_displacement = 0.0; //!< the largest displacement of any point
    MorphTimings timings;
    bool parallel = false; //!< a -parallel run: before/after hold only the invalid cells
    bool refused = false;  //!< new invalid cells, nothing written (no force)
    std::string refusal;   //!< why
    //! Checks the morphed mesh fails that the mesh before it passed, with the size of each
    //! check's first offender set (0 when it has none): each is a warning, and an error
    //! with morphDict's `newCheckFailures refuse`.
    std::vector<std::pair<std::string, Index>> new_failed_checks;
    //! With new invalid cells: the patches they touch (invalid_cells_location.h).
    std::vector<PatchCells> invalid_cells_by_patch;
    //! Faces the prescription itself folds over (folded_faces.h): refused at once, unless
    //! -force.
    FoldedFaces folded;
    //! symmetryPlane patches the morph took off their plane (OpenFOAM cannot read the mesh
    //! then: symmetry_plane_planarity.h): refused, unless -force.
    std::vector<NonPlanarSymmetryPlane> bent_symmetry_planes;
    bool written = false;
    std::filesystem::path points_file; //!< the written points file
    std::filesystem::path vtk_file;    //!< the written .vtu (if vtk)
};

} // namespace meshmorph::morph
