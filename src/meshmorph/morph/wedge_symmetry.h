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
    Index reference_patch = -1, other_patch = -1; //!< the two wedge patches
    Vector3 origin = Vector3::Zero();             //!< a point of the axis
    Vector3 axis = Vector3::UnitX();              //!< unit direction of the axis
    Vector3 normal = Vector3::UnitZ();            //!< unit normal of the reference plane
    //! Rotation about the axis taking the other plane onto the reference plane.
    Eigen::Matrix3d to_reference = Eigen::Matrix3d::Identity();
    //! A point of the reference plane and its partner on the other (to_partner: the
    //! rotation from the reference plane to the other).
    std::vector<CyclicPointPair> pairs;
    std::vector<Index> axis_points; //!< on both planes
    //! Points of one plane without a partner (a mesh that is not a clean extrusion), with
    //! the normal of their plane: they only keep their motion within it.
    std::vector<std::pair<Index, Vector3>> lone_points;

    //! Make `d` axisymmetric: pairs to their in-plane mean, axis points along the axis.
    void apply(Points& d) const;
};

//! \brief The symmetry of a wedge case: nullopt unless the mesh has exactly two wedge
//! patches with faces. Partners are matched by rotating the other plane's points onto the
//! reference plane, within 1e-3 of the point's shortest boundary edge.
std::optional<WedgeSymmetry> find_wedge_symmetry(const PolyMesh& mesh);

} // namespace meshmorph::morph
