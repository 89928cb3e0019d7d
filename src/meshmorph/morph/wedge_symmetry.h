// SPDX-License-Identifier: GPL-3.0-or-later
//! \file What keeps a morph of an axisymmetric (wedge) case axisymmetric.
//!
//! OpenFOAM's axisymmetric cases are one cell thick between two `wedge` patches, planes
//! through a common axis a small angle apart (0.1 to 5 degrees). checkMesh requires every
//! edge across the wedge to stay perpendicular to its planes and the planes to stay planar:
//! the points of one plane must move as exact rotations of their partners on the other,
//! and points on the axis along it. A space deformation fitted to the boundary gives that
//! only to round-off of its fit: a greedy RBF or the IDW correction choose their centres
//! point by point, and partners then differ by ~1e-3 of the motion, which checkMesh calls
//! thousands of edges "not aligned". As cyclic partners (cyclic_coupling.h), each pair is
//! set to the mean of its two values seen in one plane, within that plane, and rotated to
//! the other; axis points keep only their component along the axis.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/types.h"
#include "meshmorph/morph/cyclic_point_pair.h"

namespace meshmorph::morph
{

struct WedgeSymmetry
{
    Vector3 origin = Vector3::Zero(); //!< a point of the axis
    Vector3 axis = Vector3::UnitX();  //!< unit direction of the axis
    //! Rotation about the axis taking the other plane onto the reference plane.
    Eigen::Matrix3d to_reference = Eigen::Matrix3d::Identity();
    //! A point of the reference plane and its partner on the other (to_partner: the
    //! rotation from the reference plane to the other).
    std::vector<CyclicPointPair> pairs;
    std::vector<Index> axis_points; //!< on both planes
    //! Every point of either plane but the axis, with the unit normal of its plane (points
    //! without a partner, in a mesh that is not a clean extrusion, only keep within it).
    std::vector<std::pair<Index, Vector3>> plane_points;

    //! Make `d` axisymmetric: within each plane, pairs to their mean, axis points along the
    //! axis.
    void apply(Points& d) const;
};

//! \brief The symmetry of a wedge case: nullopt unless the mesh has exactly two wedge
//! patches with faces. Partners are matched by rotating the other plane's points onto the
//! reference plane, within 1e-3 of the point's shortest boundary edge.
std::optional<WedgeSymmetry> find_wedge_symmetry(const PolyMesh& mesh);

} // namespace meshmorph::morph
