// SPDX-License-Identifier: GPL-3.0-or-later
//! \file checkMesh-equivalent mesh checks and their report (docs/checkmesh-spec.md).
//!
//! check_mesh() runs OpenFOAM v1912 checkMesh's topology (§3.2), geometry (§3.3),
//! -allGeometry (§3.4) and -meshQuality (§5) checks on an in-memory PolyMesh and returns
//! both the report text checkMesh would print (from "Mesh stats" to "Mesh OK." /
//! "Failed N mesh checks.") and every number, offending face/cell/point set and per-cell
//! field, so that applications can write sets, VTK fields and JSON.
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/cell_shapes.h"
#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/quality/mesh_geometry.h"

namespace meshmorph
{

//! The meshQualityDict criteria (snappyHexMesh's, spec §5). A criterion is enabled by its
//! value exactly as in OpenFOAM (see the table in the spec); the defaults here disable all.
struct MeshQualitySettings
{
    double max_non_ortho = 180;          //!< maxNonOrtho [deg], enabled < 180
    double min_vol = -1e300;             //!< minVol, enabled > -1e15
    double min_tet_quality = -1e300;     //!< minTetQuality, enabled > -1e15
    double max_concave = 180;            //!< maxConcave [deg], enabled < 180
    double min_area = -1;                //!< minArea, enabled > -1e-15
    double max_internal_skewness = -1;   //!< maxInternalSkewness } enabled if either > 0
    double max_boundary_skewness = -1;   //!< maxBoundarySkewness }
    double min_face_weight = -1;         //!< minFaceWeight, enabled 0 <= v < 1
    double min_vol_ratio = -1;           //!< minVolRatio, enabled >= 0
    double min_twist = -2;               //!< minTwist, enabled > -1
    double min_triangle_twist = -2;      //!< minTriangleTwist, enabled > -1
    double min_face_flatness = -1;       //!< minFaceFlatness (optional key), enabled > -1e-15
    double min_determinant = -2;         //!< minDeterminant, enabled > -1
};

//! What to check and how to print.
struct CheckMeshSettings
{
    bool all_geometry = false;  //!< -allGeometry (§3.4)
    bool all_topology = false;  //!< -allTopology
    bool no_topology = false;   //!< -noTopology (skip §3.2)
    bool report_sets = false;   //!< print the "  <<Writing N ... to set X" lines (-writeSets)
    int write_precision = 6;    //!< controlDict writePrecision (%.{p}g)
    //! Compute the per-cell scaled Jacobian (not a checkMesh check; for JSON/VTK/morph).
    bool scaled_jacobian = true;
    //! -meshQuality: the criteria from system/meshQualityDict.
    std::optional<MeshQualitySettings> mesh_quality;
};

//! One offending-element set, named as checkMesh names it (nonOrthoFaces, ...).
struct MeshSet
{
    enum class Kind
    {
        face,
        cell,
        point
    };
    std::string name;
    Kind kind = Kind::face;
    std::vector<Index> labels; //!< sorted, distinct
};

//! Everything check_mesh() found. Statistics that a check did not compute are NaN / -1.
struct QualityReport
{
    std::string text; //!< checkMesh's report, "Mesh stats" .. "Mesh OK."/"Failed N mesh checks."

    Index n_points = 0, n_faces = 0, n_internal_faces = 0, n_cells = 0, n_patches = 0;
    CellShapeCounts cell_types;
    Eigen::Vector3d bounding_box_min = Eigen::Vector3d::Zero();
    Eigen::Vector3d bounding_box_max = Eigen::Vector3d::Zero();
    MeshDirections directions;

    // §3.3
    Eigen::Vector3d boundary_openness = Eigen::Vector3d::Zero();
    double max_cell_openness = 0, max_aspect_ratio = 0;
    Index open_cells = 0, high_aspect_ratio_cells = 0;
    double min_face_area = 0, max_face_area = 0;
    double min_volume = 0, max_volume = 0, total_volume = 0;
    Index negative_volume_cells = 0;
    double max_non_orthogonality = 0, avg_non_orthogonality = 0; //!< degrees
    Index severely_non_orthogonal_faces = 0, non_orthogonality_errors = 0;
    Index incorrectly_oriented_face_pyramids = 0;
    double max_skewness = 0;
    Index highly_skewed_faces = 0;

    // §3.4 (has_all_geometry)
    bool has_all_geometry = false;
    Index face_tet_errors = 0;
    double min_edge_length = 0, max_edge_length = 0;
    Index short_edges = 0;
    Index concave_faces = 0;
    double max_concave_angle = 0; //!< degrees
    double min_face_flatness = 1, avg_face_flatness = 1;
    Index warped_faces = 0;
    double min_determinant = 0, avg_determinant = 0;
    Index small_determinant_cells = 0;
    Index concave_cells = 0;
    double min_face_weight = 0, avg_face_weight = 0;
    Index low_weight_faces = 0;
    double min_volume_ratio = 0, avg_volume_ratio = 0;
    Index low_volume_ratio_faces = 0;

    // §5 (has_mesh_quality): criterion key -> faces it newly flagged
    bool has_mesh_quality = false;
    std::vector<std::pair<std::string, Index>> mesh_quality_failures;
    Index mesh_quality_faces = 0;

    //! Minimum scaled Jacobian over the cells (NaN until set by the caller).
    double min_scaled_jacobian = std::numeric_limits<double>::quiet_NaN();

    Index failed_checks = 0;
    std::vector<std::string> failed_check_names; //!< short names, in report order
    bool mesh_ok() const { return failed_checks == 0; }

    std::vector<MeshSet> sets; //!< non-empty offender sets, in report order

    //! Per-cell fields (nCells): max face non-orthogonality [deg] and skewness over the
    //! cell's faces, aspect ratio, and (with all_geometry) the checkMesh cell determinant.
    //! The determinant is always computed (printed only with all_geometry).
    Eigen::VectorXd cell_non_orthogonality, cell_skewness, cell_aspect_ratio, cell_determinant;
    //! Per-cell scaled Jacobian (nCells), when computed; min_scaled_jacobian is its minimum.
    Eigen::VectorXd cell_scaled_jacobian;
};

//! \brief Run checkMesh's checks (spec §3, §5) and build the report.
//! \param mesh a mesh with valid addressing (face vertex labels in [0, nPoints), owner and
//!        neighbour in [0, nCells)); the topology checks report everything else.
//! \param geometry compute_geometry(mesh) (passed in so callers can reuse it).
//! \throw InvalidInput if labels are out of range (files are validated by the reader).
QualityReport check_mesh(const PolyMesh& mesh, const CompactList& cell_faces,
                         const MeshGeometry& geometry, const CheckMeshSettings& settings);
//! Convenience overload computing cell_faces and the geometry.
QualityReport check_mesh(const PolyMesh& mesh, const CheckMeshSettings& settings);

//! \brief Format a scalar like OpenFOAM's Ostream with `precision` (C's %.{p}g).
std::string format_scalar(double value, int precision);

} // namespace meshmorph
