// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Closedness of the boundary and of each cell, and the cell aspect ratio (OpenFOAM
//! primitiveMeshTools::cellClosedness and primitiveMesh::checkClosedBoundary).
#pragma once

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief The boundary's openness: the sum of the boundary area vectors over the sum of
//! their magnitudes (0 for a closed boundary).
//! \param comm in a -parallel run, sums over every rank (a collective).
Vector3 boundary_openness(const PolyMesh& mesh, const MeshGeometry& geometry,
                          const parallel::Communicator* comm = nullptr);

//! Per-cell closedness fields (nCells each).
struct CellClosedness
{
    //! max over x, y, z of |sum of outward face areas| / sum of |areas| (0 when closed).
    Eigen::VectorXd openness;
    //! The largest ratio of the summed |area| components over the valid (non-empty,
    //! non-wedge) directions; in 3D at least the sum over all directions / 6 over
    //! volume^(2/3).
    Eigen::VectorXd aspect_ratio;
};

//! \brief Both fields in one pass over the cells' faces. OpenMP over cells.
CellClosedness cell_closedness(const PolyMesh& mesh, const CompactList& cell_faces,
                               const MeshGeometry& geometry, const MeshDirections& directions);

} // namespace meshmorph
