// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The empty planes of a 2D case, and what keeps a morph 2D.
//!
//! OpenFOAM's 2D cases are one cell thick between two parallel `empty` patches. A morph
//! keeps such a case 2D when both planes move identically and no point moves normal to
//! them: every prescription and every field value is evaluated at the point's projection
//! onto one reference plane, and the normal component of every displacement is removed.
#pragma once

#include <optional>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/types.h"

namespace meshmorph::morph
{

struct EmptyPlanes
{
    Vector3 normal = Vector3::UnitZ(); //!< unit normal of the planes
    double offset = 0.0;               //!< normal . x on the reference plane

    //! x projected onto the reference plane.
    Vector3 project(const Vector3& x) const { return x - (normal.dot(x) - offset) * normal; }
    //! Every row of x projected onto the reference plane.
    Points project(const Points& x) const;
    //! d without its component along the normal.
    Vector3 in_plane(const Vector3& d) const { return d - d.dot(normal) * normal; }
    //! Every row of d without its component along the normal.
    void remove_normal(Points& d) const;
};

//! \brief The empty planes of a 2D case (nullopt if the mesh has no empty patch face of
//! non-zero area). The reference plane is that of the first such face.
//! \throw InvalidInput if the empty patches are not parallel (a case morphMesh cannot
//! keep 2D).
std::optional<EmptyPlanes> find_empty_planes(const PolyMesh& mesh);

//! x projected onto the reference plane when `planes` is set; x itself otherwise.
Vector3 evaluation_position(const std::optional<EmptyPlanes>& planes, const Vector3& x);
//! d without its normal component when `planes` is set; d itself otherwise.
Vector3 in_plane(const std::optional<EmptyPlanes>& planes, const Vector3& d);

} // namespace meshmorph::morph
