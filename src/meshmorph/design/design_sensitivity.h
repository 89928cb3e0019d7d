// SPDX-License-Identifier: GPL-3.0-or-later
//! \file `morphMesh -sensitivity FILE`: dJ/da of every design variable from dJ/dx at the mesh
//! points, by the transpose product dJ/da_j = sum_i g_i . F_j(i) over the stored fields
//! (never forming more than one field at a time).
//!
//! FILE is a pointVectorField: over all points (a discrete adjoint's volume sensitivity, in
//! its internalField) or over boundary points (OpenFOAM's adjoint with `surfacePoints`
//! sensitivities: values on the design patches, the internalField zero). Each point takes
//! the value of largest magnitude among the internalField and the values of the patches it
//! lies on (fixedValue, calculated): the one that is there in either form, whether the
//! other patches and the internalField hold zeros or the same value.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "meshmorph/design/design_variant.h"

namespace meshmorph::design
{

//! What -sensitivity computed.
struct SensitivityResult
{
    std::filesystem::path input;    //!< the dJ/dx file read
    std::filesystem::path output;   //!< postProcessing/morphMesh[/<region>]/dJda written
    std::vector<std::string> names; //!< the variables
    std::vector<double> gradient;   //!< dJ/da_j
    Index nonzero_points = 0;       //!< points where dJ/dx is not zero
};

//! \brief dJ/dx of `file` (relative to the case directory unless absolute; with -parallel
//! to each processor directory, as decomposePar writes a field) over the study's mesh. \throw
//! IoError, ParseError naming the file (another mesh: a wrong size).
Points read_point_sensitivity(const DesignStudy& study, const std::filesystem::path& file);

//! \brief The same for `mesh` from the file `path` (a collective with -parallel).
Points read_point_sensitivity(const PolyMesh& mesh, const std::filesystem::path& path);

//! \brief dJ/da from `file`; writes `postProcessing/morphMesh[/<region>]/dJda` (a dictionary of
//! `<variable> <value>;`) atomically. \throw as read_point_sensitivity; IoError.
SensitivityResult design_sensitivity(DesignStudy& study, const std::filesystem::path& file);

} // namespace meshmorph::design
