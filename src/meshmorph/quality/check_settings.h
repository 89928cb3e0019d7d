// SPDX-License-Identifier: GPL-3.0-or-later
//! \file What check_mesh() checks and how it prints: checkMesh's options and the
//! meshQualityDict criteria (docs/checkmesh-spec.md §5). Plain records.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace meshmorph
{

struct QualityReport;

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
    //! Keep the per-cell fields of the face metrics (QualityReport::cell_non_orthogonality,
    //! cell_skewness, cell_determinant: what a VTK file shows). A morph that writes no VTK
    //! reads only the summary: without them its checks skip the determinant of every cell
    //! (as costly as the skewness), unless all_geometry checks it. The summary is the same.
    bool cell_fields = true;
    //! -meshQuality: the criteria from system/meshQualityDict.
    std::optional<MeshQualitySettings> mesh_quality;
    //! The report of a check of the same mesh before its points moved (a morph changes no
    //! face, cell or zone): its topology checks and tables are taken over instead of being
    //! recomputed. Serial checks without all_topology only; ignored otherwise. Its scaled
    //! Jacobian's corners (QualityReport::jacobian_corners) are reused in any check of as many
    //! cells (a -parallel morph keeps each rank's own in the reduced report).
    const QualityReport* unchanged_topology = nullptr;
    //! face_pyramid_errors of the checked points, when the caller has them already (a morph
    //! counts them after its last step, count_invalid_cells): the check takes them over
    //! instead of computing them again. Ignored unless it has an entry per face.
    const std::vector<char>* face_pyramid_errors = nullptr;
};

} // namespace meshmorph
