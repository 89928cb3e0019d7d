// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Claims: what each boundary entry prescribes for each point of its patches.
//!
//! A point on several patches gets one claim per patch; conflict_resolution.h decides
//! between them. A claim is a value (a displacement), a slip plane (the point slides within
//! it: slip and wedge patches) or nothing (type free).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/morph/decomposition.h"
#include "meshmorph/morph/empty_planes.h"
#include "meshmorph/morph/morph_setup.h"
#include "meshmorph/morph/patch_assignment.h"

namespace meshmorph::morph
{

//! One prescription claiming one point.
struct Claim
{
    enum class Kind : char
    {
        value,
        slip,
        free
    };
    Index point = 0;
    Index source = 0; //!< the patch (boundary claims) or the handle (handle claims)
    Index order = 0;  //!< its entry's position in the dictionary (wedge: -1), for first/last
    Kind kind = Kind::value;
    Vector3 value = Vector3::Zero(); //!< value: displacement; slip: unit plane normal
    Index rotation = -1;             //!< value claimed by a rotate entry: index into the rotations
};

//! What the data-driven motion types need besides the mesh.
struct ConstraintInputs
{
    //! nPoints x 3 `pointDisplacement` values (internalField with the patch values applied);
    //! required if any patch uses type pointDisplacement.
    const Points* point_displacement = nullptr;
    //! Optional per-patch values (one entry per mesh patch, nPatchPoints x 3 in patch-local
    //! order, e.g. a fixedValue boundary entry of the field); where set they replace
    //! point_displacement on that patch. Disagreements between patches are conflicts.
    const std::vector<std::optional<Points>>* patch_point_displacement = nullptr;
    //! Closest points on the target surface `file` for each row of `query` (k x 3);
    //! required if any patch uses type surface. May throw IoError/ParseError.
    std::function<Points(const std::string& file, const Points& query)> project_to_surface;
    //! assign_patches(mesh, setup) if the caller already computed it (else it is computed).
    const std::vector<PatchAssignment>* patches = nullptr;
    //! -parallel: this rank's part of the decomposed mesh (null: the whole mesh).
    const Decomposition* decomposition = nullptr;
};

//! \brief The claims of every boundary point, sorted by point (patch order within a point).
//! Closed-form motions are evaluated at the points' projections onto the reference empty
//! plane in 2D cases. \param rotations receives the rotate motions (Claim::rotation).
//! \throw ParseError/InvalidInput for a non-planar slip or wedge patch, a missing input of a
//! data-driven type, a surface that cannot be read.
std::vector<Claim> collect_claims(const PolyMesh& mesh, const MorphSetup& setup,
                                  const std::vector<PatchAssignment>& patches,
                                  const ConstraintInputs& inputs,
                                  const std::optional<EmptyPlanes>& planes,
                                  std::vector<Motion>& rotations);

} // namespace meshmorph::morph
