// SPDX-License-Identifier: GPL-3.0-or-later
//! \file checkMesh's geometry checks (checkGeometry.C; OpenFOAM primitiveMesh::check* and
//! polyMesh::check*), one function each: a metric field in, threshold, offender set and
//! verdict out. The statistics' keys are the JSON keys of checkMeshQuality -json.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/quality/check_result.h"
#include "meshmorph/quality/coupled_points.h"
#include "meshmorph/quality/edge_alignment.h"
#include "meshmorph/quality/edge_lengths.h"
#include "meshmorph/quality/wedge_alignment.h"

namespace meshmorph
{

//! \brief 2D/1D meshes: edges neither along nor across the valid directions. Fails
//! "edgeAlignment"; statistic "nonAlignedEdges"; set nonAlignedEdges (their points).
//! \param non_aligned non_aligned_edges(mesh, directions).
CheckResult check_edge_alignment(const std::vector<Edge>& non_aligned);

//! \brief Wedge meshes, in place of check_edge_alignment: the examined wedges' angles, then
//! the first wedge problem or else the edge alignment. Fails "wedgeOpposite", "wedgeAxes",
//! "wedgePlanarity" or "edgeAlignment". Statistics wedgeAngles [deg] (patch -> angle),
//! "nonAlignedEdges" and the problem's details ("wedgeAxis", "oppositeWedgeAxis",
//! "offPlanePoint", "offPlaneDistance"); set nonAlignedEdges (points).
//! \param wedges wedge_geometries(mesh). \param found wedge_findings(mesh, wedges, ...).
CheckResult check_wedges(const PolyMesh& mesh, const std::vector<WedgeGeometry>& wedges,
                         const WedgeFindings& found);

//! \brief Boundary openness above 1e-6 in some direction. Fails "boundaryOpenness";
//! statistic boundaryOpenness. \param openness boundary_openness(mesh, geometry).
CheckResult check_closed_boundary(const Vector3& openness);

//! \brief Cell openness above 1e-6 (fails "cellOpenness"), else aspect ratio above 1000
//! (fails "aspectRatio"). Statistics maxCellOpenness, maxAspectRatio, highAspectRatioCells,
//! "openCells"; sets nonClosedCells, highAspectRatioCells.
CheckResult check_closed_cells(const Eigen::VectorXd& cell_openness,
                               const Eigen::VectorXd& cell_aspect_ratio);

//! \brief Face areas below VSMALL. Fails "faceAreas"; statistics minFaceArea, maxFaceArea;
//! set zeroAreaFaces. \param face_area_magnitudes face_area_magnitudes(geometry).
CheckResult check_face_areas(const Eigen::VectorXd& face_area_magnitudes);

//! \brief Cell volumes below VSMALL. Fails "cellVolumes"; statistics minVolume, maxVolume,
//! totalVolume, negativeVolumeCells; set zeroVolumeCells.
CheckResult check_cell_volumes(const Eigen::VectorXd& cell_volumes);

//! \brief Non-orthogonality: faces above 70 degrees are severe, at 90 or more (cos <= SMALL)
//! errors. Fails "nonOrthogonality" on errors; statistics maxNonOrthogonality,
//! avgNonOrthogonality (over internal faces), severelyNonOrthogonalFaces,
//! nonOrthogonalityErrors; set nonOrthoFaces. \param orthogonality face_orthogonality().
//! \param summed per face: enters the max and average (CoupledFaces::statistics_faces()).
CheckResult check_face_orthogonality(const Eigen::VectorXd& orthogonality,
                                     const std::vector<char>& summed);

//! \brief Wrongly oriented face pyramids. Fails "facePyramids"; statistic
//! incorrectlyOrientedFacePyramids; set wrongOrientedFaces.
//! \param errors face_pyramid_errors(mesh, geometry).
CheckResult check_face_pyramids(const std::vector<char>& errors);

//! The skewness above which checkMesh counts a face as highly skewed.
inline constexpr double highly_skewed_face = 4.0;

//! \brief Skewness above 4. Fails "skewness"; statistics maxSkewness, highlySkewedFaces;
//! set skewFaces. \param skewness face_skewness(mesh, geometry).
//! \param counted per face: counted if highly skewed (CoupledFaces::master); empty: all.
CheckResult check_face_skewness(const Eigen::VectorXd& skewness,
                                const std::vector<char>& counted = {});

//! \brief Coupled point locations. Fails "coupledPoints"; statistics averageCoupledMismatch,
//! mismatchedCoupledFaces; set coupledFaces. \param match coupled_point_match(mesh, ...).
CheckResult check_coupled_points(const CoupledPointMatch& match);

//! \brief -allGeometry: face tet errors. Fails "faceTets"; statistic faceTetErrors; set
//! lowQualityTetFaces. \param errors face_tet_errors(mesh, geometry).
CheckResult check_face_tets(const std::vector<char>& errors);

//! \brief -allGeometry: edge lengths and point nearness. Never fails. Statistics
//! minEdgeLength, maxEdgeLength, "shortEdges", "nearPointDistance"; sets shortEdges (points)
//! and nearPoints: as checkMesh, the points on short edges together with the points closer
//! than the distance, present only when the near points add to the short-edge ones
//! (announced by the report's own line).
//! \param near near_points(mesh, min_length_sqr), or empty (no nearness check).
//! \param min_length_sqr the squared distance of both (checkMesh: |1e-6 * span|^2).
CheckResult check_edge_length(const EdgeLengths& lengths, const std::vector<char>& near = {},
                              double min_length_sqr = 0);

//! \brief -allGeometry: concave face corners. Never fails. Statistics concaveFaces,
//! maxConcaveAngle [deg]; set concaveFaces. \param concavity face_concavity(mesh, geometry).
CheckResult check_face_angles(const Eigen::VectorXd& concavity);

//! \brief -allGeometry: flatness below 0.8 over the faces of more than 3 points with area
//! above VSMALL. Never fails. Statistics minFaceFlatness, warpedFaces, "avgFaceFlatness",
//! "flatnessFaces" (faces measured); set warpedFaces.
CheckResult check_face_flatness(const PolyMesh& mesh, const Eigen::VectorXd& face_area_magnitudes,
                                const Eigen::VectorXd& flatness);

//! \brief -allGeometry: cell determinant below 1e-3. Fails "cellDeterminant"; statistics
//! minDeterminant, avgDeterminant, smallDeterminantCells; set underdeterminedCells.
CheckResult check_cell_determinant(const Eigen::VectorXd& cell_determinant);

//! \brief -allGeometry: concave cells. Fails "concaveCells"; statistic concaveCells; set
//! concaveCells. \param concave concave_cells(mesh, cell_faces, geometry).
CheckResult check_concave_cells(const std::vector<char>& concave);

//! \brief -allGeometry: interpolation weights below 0.05. Fails "faceWeight"; statistics
//! minFaceWeight, avgFaceWeight, lowWeightFaces; set lowWeightFaces.
//! \param weights face_weights(mesh, geometry[, coupled]).
//! \param summed per face: enters the min and average; empty: all.
CheckResult check_face_weight(const Eigen::VectorXd& weights, const std::vector<char>& summed = {});

//! \brief -allGeometry: neighbour volume ratios below 0.01. Fails "volumeRatio"; statistics
//! minVolumeRatio, avgVolumeRatio, lowVolumeRatioFaces; set lowVolRatioFaces.
//! \param ratios face_volume_ratio(mesh, geometry.cell_volumes[, coupled]).
//! \param summed per face: enters the min and average; empty: all.
CheckResult check_volume_ratio(const Eigen::VectorXd& ratios, const std::vector<char>& summed = {});

} // namespace meshmorph
