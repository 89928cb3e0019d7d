// SPDX-License-Identifier: GPL-3.0-or-later
//! \file What check_mesh() found: the record every consumer of a check reads (the report
//! text, the JSON, the -parallel reduction, morphMesh's before/after table), and the
//! function that derives its summary (failed checks, sets, headline numbers) from the
//! checks.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/cell_shapes.h"
#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/quality/check_result.h"
#include "meshmorph/quality/mesh_edges.h"
#include "meshmorph/quality/zone_topology.h"

namespace meshmorph
{

struct JacobianCorners;

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
    Index n_topology_checks = 0; //!< the leading checks that are topology checks
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
    //! The cells' corners it was computed from (topology): a later check of the same mesh
    //! with moved points (CheckMeshSettings::unchanged_topology) reuses them.
    std::shared_ptr<const JacobianCorners> jacobian_corners;
};

//! \brief From r.checks: the failed checks, the offender sets and the headline numbers.
void summarise_checks(QualityReport& r);

//! The report without its per-cell fields (the summary, the checks and the topology stay):
//! for a report kept to compare with, ~40 bytes a cell that later work can reuse.
QualityReport without_cell_fields(QualityReport r);

} // namespace meshmorph
