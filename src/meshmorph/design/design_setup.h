// SPDX-License-Identifier: GPL-3.0-or-later
//! \file `morphMesh -variables`: the one-off set-up of a design study, in one of two
//! storages (design_storage.h). `fields`: for every design variable its unit constraint set
//! (variable_constraints.h) is fitted and evaluated at every mesh point with the
//! dictionary's method, in one step (no steps, no untangling: those depend on the
//! amplitude), and stored with its prescription (design_basis.h). `shared`: one fit is
//! chosen for all of them (shared_design_fit.h) and only their prescriptions are stored.
//!
//! A variant is then x0 + sum_j a_j F_j. Each F_j is an exact morph of its unit
//! prescription (rbf, idw) or the method's least-squares fit (dmffd), so a variant is exact
//! at every constrained point to round-off. Against a one-off morph of the same amplitudes:
//! the boundary values agree (rotations linearised, see design_variables.h); with a direct
//! RBF (up to `rbf { directLimit }` constraints) and idw the interior agrees to round-off,
//! since these methods are linear in their data; the greedy RBF chooses its centres from
//! the data, so each F_j has its own centres and the interior differs by the fits'
//! tolerance pattern (measured in docs/design-variables.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "meshmorph/design/design_basis.h"
#include "meshmorph/morph/morph_result.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::design
{

//! What -variables did.
struct DesignSetupResult
{
    std::filesystem::path basis_file;
    std::string method;
    std::vector<std::string> names;
    std::vector<VariableFit> fits;
    std::vector<char> moves; //!< per variable: whether it moves any constrained point
    //! "fields" or "shared" (design_storage.h), and why (morphDict `designBasis`, or what
    //! `auto` went by). With "shared" every variable's fit statistics are the shared fit's.
    std::string storage, storage_reason;
    Index n_points = 0, n_constrained = 0; //!< n_constrained: the most of any variable
    QualityReport before;
    double seconds = 0.0;
    std::uintmax_t bytes = 0; //!< of the file written
};

//! \brief Set up the design variables of options' case and morphDict; writes the set-up
//! file atomically (nothing else). \throw ParseError, IoError, InvalidInput, SolverError.
DesignSetupResult setup_design(const morph::MorphOptions& options);

} // namespace meshmorph::design
