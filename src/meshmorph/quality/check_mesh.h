// SPDX-License-Identifier: GPL-3.0-or-later
//! \file checkMesh-equivalent mesh checks and their report (docs/checkmesh-spec.md).
//!
//! check_mesh() runs OpenFOAM v1912 checkMesh's topology (§3.2), geometry (§3.3),
//! -allGeometry (§3.4) and -meshQuality (§5) checks on an in-memory PolyMesh and returns
//! both the report text checkMesh would print (from "Mesh stats" to "Mesh OK." /
//! "Failed N mesh checks.") and every number, offending face/cell/point set and per-cell
//! field, so that applications can write sets, VTK fields and JSON.
//!
//! It is the driver of three tiers (as OpenFOAM's primitiveMeshTools -> primitiveMesh::check*
//! -> checkGeometry.C): metric functions (face_orthogonality.h, face_skewness.h, ...) return
//! per-face and per-cell fields; check functions (topology_checks.h, geometry_checks.h,
//! mesh_quality_checks.h) turn them into CheckResults; report_text.h and quality_json.h walk
//! the results. A caller that needs a few checks only calls those (see cell_validity.h).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/cell_shapes.h"
#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/quality/check_result.h"
#include "meshmorph/quality/mesh_edges.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/mesh/processor_faces.h"
#include "meshmorph/quality/zone_topology.h"

namespace meshmorph
{

//! The meshQualityDict criteria (snappyHexMesh's, spec §5). A criterion is enabled by its
//! value exactly as in OpenFOAM (see the table in the spec); the defaults here disable all.
struct MeshQualitySettings
{
    double max_non_ortho = 180;        //!< maxNonOrtho [deg], enabled < 180
    double min_vol = -1e300;           //!< minVol, enabled > -1e15
    double min_tet_quality = -1e300;   //!< minTetQuality, enabled > -1e15
    double max_concave = 180;          //!< maxConcave [deg], enabled < 180
    double min_area = -1;              //!< minArea, enabled > -1e-15
    double max_internal_skewness = -1; //!< maxInternalSkewness } enabled if either > 0
    double max_boundary_skewness = -1; //!< maxBoundarySkewness }
    double min_face_weight = -1;       //!< minFaceWeight, enabled 0 <= v < 1
    double min_vol_ratio = -1;         //!< minVolRatio, enabled >= 0
    double min_twist = -2;             //!< minTwist, enabled > -1
    double min_triangle_twist = -2;    //!< minTriangleTwist, enabled > -1
    double min_face_flatness = -1;     //!< minFaceFlatness (optional key), enabled > -1e-15
    double min_determinant = -2;       //!< minDeterminant, enabled > -1
};

//! What to check and how to print.
struct CheckMeshSettings
{
    bool all_geometry = false; //!< -allGeometry (§3.4)
    bool all_topology = false; //!< -allTopology
    bool no_topology = false;  //!< -noTopology (skip §3.2)
    bool report_sets = false;  //!< print the "  <<Writing N ... to set X" lines (-writeSets)
    int write_precision = 6;   //!< controlDict writePrecision (%.{p}g)
    //! The time directory of the check, as "Time = " names it: checkMesh writes cellToRegion
    //! there ("  <<Writing region information to "<time>/cellToRegion"").
    std::string time_name = "constant";
    //! Compute the per-cell scaled Jacobian (not a checkMesh check; for JSON/VTK/morph).
    bool scaled_jacobian = true;
    //! -meshQuality: the criteria from system/meshQualityDict.
    std::optional<MeshQualitySettings> mesh_quality;
};

//! Everything check_mesh() found: the mesh statistics, the topology tables, every check's
//! result in report order, and per-cell fields for VTK output.
struct QualityReport
{
    std::string text; //!< checkMesh's report, "Mesh stats" .. "Mesh OK."/"Failed N mesh checks."

    //! In a -parallel run (reduce_report()), what checkMesh -parallel prints in "Mesh stats":
    //! the ranks' counts summed (shared points and processor faces once per rank), and the
    //! patches without the processor patches (with the range of patches per rank).
    struct ParallelStats
    {
        int ranks = 1;
        Index summed_points = 0, summed_faces = 0, summed_internal_faces = 0;
        Index non_processor_patches = 0, min_patches = 0, max_patches = 0;
        Index processor_faces = 0; //!< summed: each processor face twice
    };
    std::optional<ParallelStats> parallel;

    // "Mesh stats" and the cell types (in a -parallel run, of the undecomposed mesh: points
    // and faces shared by ranks count once, processor faces are internal faces).
    Index n_points = 0, n_faces = 0, n_internal_faces = 0, n_cells = 0, n_patches = 0;
    Index n_point_zones = 0, n_face_zones = 0, n_cell_zones = 0;
    Index n_internal_points = -1;    //!< -1 when the boundary points do not come last
    std::optional<EdgeCounts> edges; //!< with all_topology, when n_internal_points >= 0
    CellShapeCounts cell_types;
    Eigen::Vector3d bounding_box_min = Eigen::Vector3d::Zero();
    Eigen::Vector3d bounding_box_max = Eigen::Vector3d::Zero();
    MeshDirections directions;

    // The topology tables (empty with no_topology).
    std::vector<SurfaceTopology> patch_topology, face_zone_topology;
    //! checkMesh's pointSet nonManifoldPoints: the surfaces' edge_points and fan_points,
    //! sorted (none in a -parallel run, as checkMesh -parallel); and their number.
    std::vector<Index> non_manifold_points;
    Index non_manifold_total = 0;
    std::vector<CellZoneSummary> cell_zones;

    //! Every check run, in report order: topology, geometry, -allGeometry, -meshQuality.
    std::vector<CheckResult> checks;
    //! The statistic `key` (a JSON key, e.g. "minVolume") of any check, or nullptr.
    const Statistic* statistic(std::string_view key) const;

    // Headline numbers, copied from the checks' statistics (0 when not computed).
    Index negative_volume_cells = 0;              //!< negativeVolumeCells
    Index incorrectly_oriented_face_pyramids = 0; //!< incorrectlyOrientedFacePyramids
    Index face_tet_errors = 0;                    //!< faceTetErrors (with all_geometry)
    double max_non_orthogonality = 0;             //!< maxNonOrthogonality [deg]
    double max_skewness = 0;                      //!< maxSkewness
    double max_aspect_ratio = 0;                  //!< maxAspectRatio
    double total_volume = 0;                      //!< totalVolume
    double min_determinant = 0;                   //!< minDeterminant (with all_geometry)

    //! Minimum scaled Jacobian over the cells (NaN until set by the caller).
    double min_scaled_jacobian = std::numeric_limits<double>::quiet_NaN();

    Index failed_checks = 0;
    std::vector<std::string> failed_check_names; //!< short names, in report order
    bool mesh_ok() const { return failed_checks == 0; }

    std::vector<MeshSet> sets; //!< non-empty offender sets, in report order
    //! Per cell its region (cell_regions), when the mesh has several regions: checkMesh's
    //! <time>/cellToRegion. Empty otherwise, and with no_topology.
    std::vector<Index> cell_to_region;

    //! Per-cell fields (nCells): max face non-orthogonality [deg] and skewness over the
    //! cell's faces, aspect ratio, and the checkMesh cell determinant (always computed,
    //! reported only with all_geometry).
    Eigen::VectorXd cell_non_orthogonality, cell_skewness, cell_aspect_ratio, cell_determinant;
    //! Per-cell scaled Jacobian (nCells), when computed; min_scaled_jacobian is its minimum.
    Eigen::VectorXd cell_scaled_jacobian;
};

//! \brief Run checkMesh's checks (spec §3, §5) and build the report.
//! \param mesh a mesh with valid addressing (face vertex labels in [0, nPoints), owner and
//!        neighbour in [0, nCells)); the topology checks report everything else.
//! \param geometry compute_geometry(mesh) (passed in so callers can reuse it).
//! \param processors in a -parallel run (a collective then), this rank's processor faces
//!        (exchange_processor_faces): they are checked as coupled faces, and the regions, the
//!        bounding box, the directions and the boundary openness are global; the rest of the
//!        report is this rank's, reduce_report() (parallel_report.h) combines the ranks.
//! \throw InvalidInput if labels are out of range (files are validated by the reader).
QualityReport check_mesh(const PolyMesh& mesh, const CompactList& cell_faces,
                         const MeshGeometry& geometry, const CheckMeshSettings& settings,
                         const ProcessorFaces* processors = nullptr);
//! Convenience overload computing cell_faces and the geometry.
QualityReport check_mesh(const PolyMesh& mesh, const CheckMeshSettings& settings);

//! \brief From r.checks: the failed checks, the offender sets and the headline numbers.
void summarise_checks(QualityReport& r);

//! \brief Format a scalar like OpenFOAM's Ostream with `precision` (C's %.{p}g).
std::string format_scalar(double value, int precision);

} // namespace meshmorph
