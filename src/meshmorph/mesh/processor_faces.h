// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The processor patches of a decomposed mesh as checkMesh -parallel couples them.
//!
//! decomposePar writes, for each pair of neighbouring ranks A < B, a patch procBoundaryAtoB
//! on A and procBoundaryBtoA on B with the same faces in the same order, each oriented
//! outwards from its own side (so the vertices run the other way round). A processor face is
//! a coupled face: checkMesh measures it against the cell on the other rank (syncTools'
//! swapBoundaryCellPositions), and the rank with the lower number holds the statistics of
//! the pair (processorPolyPatch::owner()).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph
{

//! One processor patch with faces.
struct ProcessorPatch
{
    Index patch = -1;        //!< index in mesh.patches
    int neighbour_rank = -1; //!< neighbProcNo
    bool owner = false;      //!< this rank's number is below the neighbour's
};

//! \brief The `processor` patches of a decomposed mesh with faces, in patch order.
//! \throws InvalidInput if a patch's myProcNo is not `rank`, if neighbProcNo is missing, or
//!         for processorCyclic patches (a cyclic across ranks, not supported yet).
std::vector<ProcessorPatch> processor_patches(const PolyMesh& mesh, int rank);

//! What lies across the processor faces of this rank, received from the neighbours.
struct ProcessorFaces
{
    const parallel::Communicator* comm = nullptr;
    std::vector<ProcessorPatch> patches;
    //! Per boundary face (face - nInternalFaces): the neighbour rank's owner cell centre and
    //! volume on processor faces (untransformed: decomposed ranks share one frame).
    Points neighbour_cell_centres;
    Eigen::VectorXd neighbour_cell_volumes;
    //! Per boundary face: the neighbour's vertices of the coupled face, in its own order
    //! (empty off processor patches).
    std::vector<std::vector<Vector3>> neighbour_face_points;
    //! Per boundary face: 1 on a processor patch, and 1 if this rank owns that patch.
    std::vector<char> on_processor_patch, owner_side;
};

//! \brief Exchange the owner cell centres, cell volumes and face vertices of every processor
//! face with the neighbouring ranks (a collective: every rank calls it).
//! \throws InvalidInput if a neighbour's patch has a different number of faces.
ProcessorFaces exchange_processor_faces(const PolyMesh& mesh, const MeshGeometry& geometry,
                                        const parallel::Communicator& comm);

//! \brief Per boundary face, the value the neighbouring rank has on the coupled face (its
//! `values` of the same face), for processor faces; 0 elsewhere. A collective.
//! \param values one per boundary face (face - nInternalFaces).
std::vector<double> swap_processor_values(const PolyMesh& mesh, const ProcessorFaces& processors,
                                          const std::vector<double>& values);

} // namespace meshmorph
