// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Whether coupled faces start at opposite points (checkMesh's checkCoupledPoints): on
//! the owner side of each cyclic, vertex 0 of a face must meet vertex 0 of its coupled face,
//! and the rest in reverse order, once the neighbour's points are transformed to this side.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/coupled_patches.h"

namespace meshmorph
{

//! The outcome of comparing the coupled faces' points.
struct CoupledPointMatch
{
    //! Faces (owner side) with a point further than face_tolerances() from its partner.
    std::vector<Index> mismatched_faces;
    //! The mean distance over the points compared before any mismatch (0 if none).
    double average_mismatch = 0;
};

//! \brief Compare every owner-side cyclic face with its coupled face, point by point.
//! \param cyclics cyclic_patches(mesh, geometry).
//! \throws InvalidInput if a face and its coupled face differ in size.
//! \param processors in a -parallel run, the processor faces (compared on the owner side).
CoupledPointMatch coupled_point_match(const PolyMesh& mesh, const MeshGeometry& geometry,
                                      const std::vector<CyclicPatch>& cyclics,
                                      const ProcessorFaces* processors = nullptr);

} // namespace meshmorph
