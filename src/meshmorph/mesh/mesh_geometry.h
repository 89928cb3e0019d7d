// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Face centres/areas, cell centres/volumes and mesh directions, bit-exact to OpenFOAM.
//!
//! Implements docs/checkmesh-spec.md §2: face centre = area-weighted centroid of the triangle
//! fan around the vertex average; cell centre = volume-weighted centroid of the face pyramids
//! about the mean of the face centres; signed volumes. Summation orders follow OpenFOAM's
//! primitiveMesh so that every printed checkMesh number is reproduced.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/wedge_geometry.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph
{

//! The base geometry of a mesh.
struct MeshGeometry
{
    Points face_centres;          //!< nFaces x 3, Cf
    Points face_areas;            //!< nFaces x 3, area vectors Af (owner -> neighbour / outwards)
    Points cell_centres;          //!< nCells x 3, Cc
    Eigen::VectorXd cell_volumes; //!< nCells, signed (inverted cells are negative)
};

//! \brief Face centres and area vectors (spec §2.1). OpenMP over faces.
//! \param mesh the mesh; face vertex labels must be in [0, nPoints).
//! \param centres, areas outputs, resized to nFaces x 3.
void face_centres_and_areas(const PolyMesh& mesh, Points& centres, Points& areas);

//! \brief Row f of centres and areas, as face_centres_and_areas computes it (a mesh
//! repair that moves a few points updates the geometry of their faces with it).
void face_centre_and_area(const PolyMesh& mesh, Index f, Points& centres, Points& areas);

//! \brief The area vector of face f alone, as face_centres_and_areas computes it.
Vector3 face_area_vector(const PolyMesh& mesh, Index f);

//! \brief Cell centres and signed volumes (spec §2.2) from g's face geometry, into g.
//! \param cell_faces from meshmorph::cell_faces(mesh) (owned faces first, each part in face
//!        order: the accumulation order of OpenFOAM's owner and neighbour passes).
//! A cell without faces gets centre (0,0,0) and volume 0... as OpenFOAM would divide by
//! zero there, such meshes fail the topology checks first.
void cell_centres_and_volumes(const PolyMesh& mesh, const CompactList& cell_faces, MeshGeometry& g);

//! \brief Cell c's centre and volume in g, as cell_centres_and_volumes computes them.
void cell_centre_and_volume(const PolyMesh& mesh, const CompactList& cell_faces, Index c,
                            MeshGeometry& g);

//! \brief All of the above. \pre valid face and cell addressing (see check_mesh for the
//! checks that make sure of it).
MeshGeometry compute_geometry(const PolyMesh& mesh, const CompactList& cell_faces);
MeshGeometry compute_geometry(const PolyMesh& mesh);

//! \brief |Af| per face (nFaces), OpenFOAM's magSf. OpenMP over faces.
Eigen::VectorXd face_area_magnitudes(const MeshGeometry& geometry);

//! The geometric and solution directions (spec §2.4): +1 valid, -1 empty/wedge direction.
struct MeshDirections
{
    Eigen::Vector3i geometric{1, 1, 1};
    Eigen::Vector3i solution{1, 1, 1};
    int n_geometric() const { return (geometric.array() == 1).count(); }
    int n_solution() const { return (solution.array() == 1).count(); }
    bool has_wedges = false;
};

//! \brief geometricD and solutionD (OpenFOAM polyMesh::calcDirections): a direction is
//! empty where the summed |area| of the empty patches' faces has a unit component above
//! 1e-6; geometricD also drops the directions of the wedges' centre normals.
//! \param wedges wedge_geometries(mesh).
//! \param comm in a -parallel run, sums the empty faces' areas over every rank (a collective).
MeshDirections mesh_directions(const PolyMesh& mesh, const Points& face_areas,
                               const std::vector<WedgeGeometry>& wedges,
                               const parallel::Communicator* comm = nullptr);
//! Convenience overload computing wedge_geometries(mesh).
MeshDirections mesh_directions(const PolyMesh& mesh, const Points& face_areas);

} // namespace meshmorph
