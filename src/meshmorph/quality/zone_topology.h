// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The rows of checkMesh's patch / faceZone topology and cellZone addressing tables
//! (checkTopology.C: PrimitivePatch::surfaceType, cellZone points, volume and bounds).
#pragma once

#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! A set of faces (a patch or a faceZone) seen as a surface.
struct SurfaceTopology
{
    std::string name;
    Index n_faces = 0;
    Index n_points = 0; //!< distinct points
    std::string type;   //!< "ok (closed singly connected)", "multiply connected (shared edge)", ...
    Vector3 bb_min = Vector3::Zero(), bb_max = Vector3::Zero(); //!< of the points, if any
    //! checkMesh's nonManifoldPoints of this surface: the points of edges used by more than
    //! two faces (PrimitivePatch::checkTopology), and of a closed surface the points whose
    //! faces form several fans (checkPointManifold). Sorted.
    std::vector<Index> edge_points, fan_points;
};

//! \brief The surface type of `faces` (OpenFOAM PrimitivePatch::surfaceType): an edge used
//! by more than two faces makes it multiply connected; an edge used once, non-closed; a
//! closed surface whose faces around some point form several fans, multiply connected.
SurfaceTopology surface_topology(const PolyMesh& mesh, std::string name,
                                 const std::vector<Index>& faces);

//! \brief One row per patch, then (second) one per faceZone.
std::vector<SurfaceTopology> patch_topology(const PolyMesh& mesh);
std::vector<SurfaceTopology> face_zone_topology(const PolyMesh& mesh);

//! A cellZone's addressing summary.
struct CellZoneSummary
{
    std::string name;
    Index n_cells = 0, n_points = 0;
    double volume = 0;      //!< sum of the cell volumes, in zone order
    Vector3 bb_min, bb_max; //!< of its points (+-VGREAT when it has none)
};

//! \brief One row per cellZone.
std::vector<CellZoneSummary> cell_zone_summaries(const PolyMesh& mesh,
                                                 const CompactList& cell_faces,
                                                 const MeshGeometry& geometry);

} // namespace meshmorph
