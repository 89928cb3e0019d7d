// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The geometry OpenFOAM derives for each wedge patch (wedgePolyPatch::calcGeometry):
//! its mean normal, the coordinate plane it leans from, the wedge angle and the axis. The
//! mesh directions and checkMesh's wedge check are computed from these, not from face areas.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! One non-empty wedge patch, as wedgePolyPatch sees it.
struct WedgeGeometry
{
    Index patch = -1; //!< index in mesh.patches
    //! n(): the plain average of the faces' unit normals (not renormalised).
    Vector3 normal = Vector3::Zero();
    //! centreNormal(): the unit normal of the coordinate plane the wedge leans from, i.e.
    //! `normal` with each component c mapped to sign(c) * (max(|c|, 0.5) - 0.5), normalised.
    //! Zero if no component of `normal` exceeds 0.5 in magnitude (OpenFOAM refuses such a
    //! mesh when reading it).
    Vector3 centre_normal = Vector3::Zero();
    double cos_angle = 0;           //!< cosAngle(): centre_normal . normal
    Vector3 axis = Vector3::Zero(); //!< axis(): centre_normal x normal, normalised
};

//! \brief The geometry of wedge patch `patch` (type "wedge", at least one face), in
//! OpenFOAM's operation order (face unit normals by face::unitNormal).
WedgeGeometry wedge_geometry(const PolyMesh& mesh, Index patch);

//! \brief wedge_geometry() of every wedge patch with faces, in patch order.
std::vector<WedgeGeometry> wedge_geometries(const PolyMesh& mesh);

} // namespace meshmorph
