// SPDX-License-Identifier: GPL-3.0-or-later
//! \file checkMesh's topology checks (checkTopology.C, OpenFOAM primitiveMesh::checkCells,
//! checkPoints, checkUpperTriangular, checkFaceVertices, checkCellsZipUp, checkFaceFaces),
//! one function each, returning a CheckResult (text-only statistics: checkMesh's JSON has
//! no topology keys).
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/processor_faces.h"
#include "meshmorph/quality/cell_edge_usage.h"
#include "meshmorph/quality/check_result.h"
#include "meshmorph/quality/face_face_connectivity.h"

namespace meshmorph
{

//! \brief Patches contiguous from nInternalFaces to nFaces, names unique. Never fails
//! (checkMesh prints an error line only). Statistic "boundaryDefinitionOK" (0/1).
CheckResult check_boundary_definition(const PolyMesh& mesh);

//! \brief The empty patches' face count is a multiple of nCells (a 1D/2D mesh). Never fails.
//! Statistic "emptyFacesDivisible" (0/1).
CheckResult check_empty_patches(const PolyMesh& mesh);

//! \brief Cells with fewer than 4 faces or out-of-range face labels. Fails "illegalCells";
//! statistic "illegalCells"; set illegalCells.
CheckResult check_cell_addressing(const PolyMesh& mesh, const CompactList& cell_faces);

//! \brief Points used by no face. Fails "unusedPoints"; statistic "unusedPoints"; set
//! unusedPoints.
CheckResult check_point_usage(const PolyMesh& mesh);

//! \brief Internal faces in upper-triangular order (owner < neighbour, each cell's faces in
//! neighbour order). Fails "upperTriangular"; statistic "cellsWithMultipleFaces" (cells
//! with several faces to one neighbour); set upperTriangularFace.
CheckResult check_upper_triangular(const PolyMesh& mesh, const CompactList& cell_faces);

//! \brief Faces repeating a vertex (out-of-range labels are rejected earlier). Fails
//! "faceVertices"; statistic "faceVertexErrors"; set outOfRangeFaces.
CheckResult check_face_vertices(const PolyMesh& mesh);

//! \brief -allTopology: cells with an edge used by one face only. Fails "cellsZipUp";
//! statistic "openCells"; set zipUpCells (open and over-used cells).
CheckResult check_cells_zip_up(const CellEdgeUsage& usage);

//! \brief -allTopology: duplicate faces and non-consecutive shared points. Never fails.
//! Statistics "baffleFaces", "duplicateFaces", "nonConsecutiveFaces"; set edgeFaces (both
//! faces of every such pair, baffles included).
CheckResult check_face_faces(const FaceFaceConnectivity& connectivity);

//! \brief -allTopology: cells with zero or one, and with two, internal or coupled faces (sets
//! oneInternalFaceCells, twoInternalFacesCells); processor faces are coupled faces. Never
//! fails.
CheckResult check_internal_face_cells(const PolyMesh& mesh,
                                      const ProcessorFaces* processors = nullptr);

//! \brief The number of cell regions. Never fails. Statistic "regions"; with several, sets
//! region0, region1, ... (announced by the report's own lines), and with all_topology (as
//! checkTopology.C) statistic "regionDisconnected" (per region set name: 1 when no boundary
//! point of the region is on a boundary face of another region, 0 when "point connected")
//! and set multiRegionPoints (the boundary points shared by regions).
//! \param regions cell_regions(mesh).
CheckResult check_regions(const PolyMesh& mesh, const std::vector<std::vector<Index>>& regions,
                          bool all_topology);

} // namespace meshmorph
