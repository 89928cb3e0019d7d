// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The constraint set of each design variable at unit amplitude.
//!
//! Variables add up: the morphDict's `boundary` entries say what stays fixed, slips or is
//! free; every patch that any variable moves is held fixed (zero) in the other variables'
//! sets and moves by its unit motion in its own, so a patch moved by two variables moves by
//! the sum of their motions. A handle that a variable moves is left out of the other
//! variables' sets (its points follow their fields: a front-wheel handle adds to a lift of
//! the whole bike); handles that no variable names keep pinning their points. The `boundary`
//! entries themselves must not move anything (a motion there belongs in a design
//! variable): that keeps x0 the zero variant.
#pragma once

#include <array>
#include <map>
#include <utility>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/design/design_variables.h"
#include "meshmorph/morph/constraint_set.h"
#include "meshmorph/morph/decomposition.h"
#include "meshmorph/morph/morph_setup.h"
#include "meshmorph/morph/point_displacement_input.h"

namespace meshmorph::design
{

//! The unit constraint sets of a design study.
class VariableConstraints
{
public:
    //! \param point_displacement the case's pointDisplacement field, if any variable has type
    //! pointDisplacement (else null).
    //! \throw ParseError/InvalidInput naming the dictionary entry: a moving boundary entry or
    //! handle that is no variable, an unknown patch or handle, a handle variable's handle
    //! that is missing.
    //! \param decomposition -parallel: this rank's part (null: the whole mesh); then unit()
    //! and moves_anything() are collectives.
    VariableConstraints(const PolyMesh& mesh, const morph::MorphSetup& base,
                        const DesignVariables& variables,
                        const morph::PointDisplacementInputs* point_displacement,
                        const morph::Decomposition* decomposition = nullptr);

    //! \brief The constraints of variable j at amplitude 1 (rotations linearised).
    //! \throw InvalidInput naming the variable when its set resolves to no motion (check
    //! moves_anything() first for lattice variables).
    morph::Constraints unit(Index j) const;

    //! Whether variable j moves any constrained point (a lattice control point whose support
    //! holds none of its patches' points does not).
    bool moves_anything(Index j) const;

    //! The points of this rank's mesh on the patches variable j moves (a point on two of
    //! them twice).
    std::vector<Index> points_moved_by(Index j) const;

private:
    bool moves_any_local_point(Index j) const;
    //! A lattice's B-spline weights at the points of its patches: per control point as
    //! written (i, j, k), the points in its support and its weight there (summed over an
    //! axis written with count 1). Computed once per lattice: its variables share it.
    using PointWeights = std::vector<std::pair<Index, double>>;
    const PointWeights& control_weights(Index j) const;
    //! A lattice variable's unit prescription: its weight times its direction at the points
    //! of its patches, zero elsewhere.
    Points lattice_field(Index j) const;

    const PolyMesh& mesh_;
    morph::MorphSetup base_; //!< handles' displacements zero
    const DesignVariables& variables_;
    const morph::PointDisplacementInputs* point_displacement_;
    const morph::Decomposition* decomposition_;
    std::vector<morph::PatchAssignment> frozen_;   //!< every patch a variable moves: fixed
    std::vector<std::vector<char>> moved_patches_; //!< per variable: its patches
    //! Per lattice, once computed: control point (i, j, k) -> its points and weights.
    mutable std::vector<std::map<std::array<int, 3>, PointWeights>> lattice_weights_;
};

} // namespace meshmorph::design
