// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The stages of a morph of a case, public so that front ends other than morphMesh
//! (the Python module) can run them in memory: read the mesh, read the morphDict, resolve
//! the prescriptions into constraints, check, fit and evaluate in steps, judge, write.
//! morph_case() (morph_case.h) is these stages in order.
#pragma once

#include <filesystem>
#include <optional>

#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/morph/before_check.h"
#include "meshmorph/morph/decomposition.h"
#include "meshmorph/morph/deformation_settings.h"
#include "meshmorph/morph/morph_result.h"
#include "meshmorph/morph/morph_setup.h"
#include "meshmorph/morph/morph_steps.h"
#include "meshmorph/morph/point_displacement_input.h"

namespace meshmorph::morph
{

//! A case read for a morph: the morphDict's settings and the mesh (this rank's part in a
//! -parallel run).
struct MorphCase
{
    std::filesystem::path case_dir, dict_path, mesh_case;
    MorphSetup setup;
    DeformationSettings settings;
    StepSettings step_settings;
    //! morphDict `newCheckFailures refuse`: a check the morph makes fail refuses the morph
    //! (default `warn`: a warning, and the JSON's newFailedChecks).
    bool refuse_new_check_failures = false;
    io::FoamPolyMesh foam;
    Decomposition decomposition;
    const Decomposition* parts(const MorphOptions& o) const
    {
        return o.parallel ? &decomposition : nullptr;
    }
};

//! `<case>/system[/<region>]/morphDict`, or options.dict (relative to the case).
std::filesystem::path morph_dict_path(const MorphOptions& options,
                                      const std::filesystem::path& case_dir);

//! \brief Read the morphDict of options into `in` (setup, settings, step settings); sets
//! in.case_dir and in.dict_path, and result.method. \throw IoError, ParseError.
void read_morph_dict(const MorphOptions& options, MorphCase& in, MorphResult& result);

//! \brief Read the mesh of options (a collective with -parallel) into `in`.
//! \pre in.case_dir is set (read_morph_dict, or by the caller). \throw IoError, ParseError.
void read_morph_mesh(const MorphOptions& options, MorphCase& in, MorphResult& result);

//! \brief The prescriptions of in.setup resolved into result.constraints (surfaces and the
//! pointDisplacement field read as the entries need them; `given` replaces the field).
//! \throw ParseError, InvalidInput, IoError.
void resolve_constraints(const MorphOptions& options, const MorphCase& in, MorphResult& result,
                         const PointDisplacementInputs* given = nullptr);

//! \brief Refuse output options this build or run cannot honour (-vtk with -parallel or
//! without VTK). \throw InvalidInput.
void check_output_options(const MorphOptions& options);

//! \brief Fit and evaluate the resolved constraints in steps, check the result and judge
//! it (result.before from `before`, result.after, result.refused). Writes nothing.
//! \param before the check of in.foam.mesh (possibly still running).
//! \param moved receives the morphed mesh: in's topology, copied after the fit (so that the
//! copy does not add to the fit's peak memory) unless the caller keeps one from an earlier
//! morph, or moved out of `spent`.
//! \param spent in.foam.mesh itself when the caller needs it no more after the morph (a
//! single morph of a case): the steps work in it (morph_in_steps in_place) and it becomes
//! the morphed mesh, so the faces and cells are never copied (45 MB on the motorBike).
void morph_resolved(const MorphOptions& options, const MorphCase& in, const CompactList& cf,
                    BeforeCheck& before, MorphResult& result, std::optional<PolyMesh>& moved,
                    PolyMesh* spent = nullptr);

//! \brief Write the morphed points to result.output_instance (and the VTK file if asked).
void write_morph_result(const MorphOptions& options, const MorphCase& in, const PolyMesh& moved,
                        MorphResult& result);

//! The instance the points go to: the mesh's own with -overwrite, else the next time.
std::string morph_output_instance(const MorphOptions& options, const MorphCase& in);

} // namespace meshmorph::morph
