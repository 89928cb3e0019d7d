// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The wedge check of axisymmetric meshes (checkMesh's checkWedges, which replaces
//! the edge alignment check when wedges knock out a geometric direction): every wedge has an
//! opposite wedge about the same axis and is planar, and every edge off the wedges lies
//! along the valid directions or across them.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/mesh/wedge_geometry.h"
#include "meshmorph/quality/edge_alignment.h"

namespace meshmorph
{

//! What checkWedges finds. It walks the wedges in patch order and stops at the first
//! problem, so only the wedges up to that one are reported.
struct WedgeFindings
{
    enum class Problem
    {
        none,           //!< every wedge is sound; non_aligned holds the edge check's result
        no_opposite,    //!< the last examined wedge has no opposite wedge
        different_axes, //!< ... its opposite wedge has another axis (checkWedges tests
                        //!< it, though the opposite wedge search already requires the axis)
        not_planar      //!< ... one of its points is off its plane
    };
    std::size_t n_examined = 0; //!< the first n_examined wedges were examined
    Problem problem = Problem::none;
    Vector3 opposite_axis = Vector3::Zero();   //!< different_axes: the opposite wedge's axis
    Vector3 off_plane_point = Vector3::Zero(); //!< not_planar: the first point off the plane
    double off_plane_distance = 0;             //!< not_planar: its distance from the plane
    //! none: the edges, not on a wedge, neither along nor across the valid directions
    //! (as non_aligned_edges()).
    std::vector<Edge> non_aligned;
};

//! \brief The index in `wedges` of the wedge opposite wedges[i] (OpenFOAM's
//! findOppositeWedge: as many faces, the same axis within 1e-3, and a normal whose angle to
//! wedges[i]'s centre normal differs from wedges[i]'s), or -1.
Index opposite_wedge(const PolyMesh& mesh, const std::vector<WedgeGeometry>& wedges, std::size_t i);

//! \brief checkWedges' findings. \param wedges wedge_geometries(mesh).
//! \param directions mesh_directions(mesh, ..., wedges).
WedgeFindings wedge_findings(const PolyMesh& mesh, const std::vector<WedgeGeometry>& wedges,
                             const MeshDirections& directions);

} // namespace meshmorph
