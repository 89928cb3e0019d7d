// SPDX-License-Identifier: GPL-3.0-or-later
//! \file What every design-study command reads first: the morphDict (its settings, its
//! design variables, its fingerprint), the mesh, and where the set-up lives.
#pragma once

#include <filesystem>
#include <string>

#include "meshmorph/design/design_storage.h"
#include "meshmorph/design/design_variables.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/morph/decomposition.h"
#include "meshmorph/morph/deformation_settings.h"
#include "meshmorph/morph/morph_result.h"
#include "meshmorph/morph/morph_setup.h"
#include "meshmorph/morph/point_displacement_input.h"

namespace meshmorph::design
{

struct DesignBasisHeader;

//! A case read for a design study.
struct DesignCase
{
    //! mesh_case: the case, or in a -parallel run this rank's processor<rank> directory
    //! (its mesh, its set-up file, its time directories).
    std::filesystem::path case_dir, mesh_case, dict_path, basis_path;
    std::string dict_fingerprint; //!< of the morphDict's bytes
    morph::MorphSetup setup;
    morph::DeformationSettings settings;
    DesignVariables variables;
    bool untangle = true;            //!< morphDict `untangle`: repair a variant's new invalid cells
    Index max_untangle_cells = 1000; //!< morphDict `maxUntangleCells` (morph_steps.h)
    //! morphDict `newCheckFailures refuse`: a variant failing a check the set-up's mesh
    //! passed is refused (default: a warning, and the report's newFailedChecks).
    bool refuse_new_check_failures = false;
    DesignStorage storage = DesignStorage::fields; //!< morphDict `designBasis`
    io::FoamPolyMesh foam;
    bool parallel = false;
    morph::Decomposition decomposition; //!< -parallel: this rank's part
    const morph::Decomposition* parts() const { return parallel ? &decomposition : nullptr; }
};

//! `<case>` or, with -parallel, `<case>/processor<rank>` (the MPI session must be running).
std::filesystem::path design_mesh_case(const morph::MorphOptions& options);

//! \brief Read the morphDict and the mesh of options.case_dir (options.time; a design
//! command without -time reads the instance its set-up was made on, see design_variant.h).
//! With -parallel every rank reads its processor directory's mesh (a collective).
//! \throw ParseError, IoError; InvalidInput when the dictionary has no designVariables.
DesignCase read_design_case(const morph::MorphOptions& options);

//! The case's pointDisplacement field when a design variable reads it (a collective with
//! -parallel), else empty: what VariableConstraints takes.
morph::PointDisplacementInputs read_variable_fields(const DesignCase& dc,
                                                    const morph::MorphOptions& options);

//! \brief Refuse a set-up that was made for other points, topology or dictionary.
//! \throw InvalidInput saying which differs and to run morphMesh -variables again.
void require_current(const DesignCase& dc, const DesignBasisHeader& header,
                     const std::string& basis_file);

} // namespace meshmorph::design
