// SPDX-License-Identifier: GPL-3.0-or-later
// checkMesh's geometry checks: sums run serially in storage order, so the numbers do not
// depend on the number of threads; extremes and the lists of failing faces (which do not
// depend on an order) are found on every thread.
#include "meshmorph/quality/geometry_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "meshmorph/mesh/foam_vector.h"
#include "meshmorph/quality/face_orthogonality.h"

namespace meshmorph
{

namespace
{

constexpr double small = constants::small;
constexpr double vsmall = constants::vsmall;
constexpr double great = constants::great;

//! The elements with errors[i] > 0 and the sum of the errors.
std::pair<Index, std::vector<Index>> error_faces(const std::vector<char>& errors)
{
    Index total = 0;
    std::vector<Index> faces;
    for (std::size_t f = 0; f < errors.size(); ++f)
        if (errors[f])
        {
            total += errors[f];
            faces.push_back(static_cast<Index>(f));
        }
    return {total, std::move(faces)};
}

//! The indices f in [0, n) with is(f), ascending: the rare faces a check lists. The tests
//! run on every thread (per_face_flags), the short list is gathered in order.
template <class Predicate> std::vector<Index> faces_where(Index n, const Predicate& is)
{
    return error_faces(detail::per_face_flags(n, is)).second;
}

//! Minimum, maximum and sum of a field (in storage order) and the elements below a threshold.
struct FieldRange
{
    double min = great, max = -great, sum = 0;
    std::vector<Index> below;
};

FieldRange field_range(const Eigen::VectorXd& values, double threshold)
{
    FieldRange r;
    for (Eigen::Index i = 0; i < values.size(); ++i)
    {
        // A value that is not a number (a point at inf or NaN) is below every threshold:
        // such geometry is invalid, and checkMesh itself stops with a floating-point error.
        if (!(values[i] >= threshold))
            r.below.push_back(static_cast<Index>(i));
        r.min = std::min(r.min, values[i]);
        r.max = std::max(r.max, values[i]);
        r.sum += values[i];
    }
    return r;
}

//! A check of an internal-face field whose minimum and average are reported and whose
//! values below a threshold fail (face weights, volume ratios).
struct LowValueCheck
{
    CheckId id;
    const char* min_key;
    const char* avg_key;
    const char* count_key;
    double threshold;
    const char* failure;
    const char* set;
    const char* description;
};

//! Values below the threshold over all faces; min and average over the `summed` ones (all if
//! empty): checkMesh counts both sides of a coupled face but averages its owner side only.
CheckResult check_low_values(const LowValueCheck& spec, const Eigen::VectorXd& values,
                             const std::vector<char>& summed)
{
    FieldRange range;
    Index n = 0;
    for (Eigen::Index i = 0; i < values.size(); ++i)
    {
        if (values[i] < spec.threshold)
            range.below.push_back(static_cast<Index>(i));
        if (summed.empty() || summed[static_cast<std::size_t>(i)])
        {
            range.min = std::min(range.min, values[i]);
            range.sum += values[i];
            ++n;
        }
    }
    CheckResult r(spec.id);
    r.add(spec.min_key, n > 0 ? range.min : 0.0);
    r.add_average(spec.avg_key, n > 0 ? range.sum / static_cast<double>(n) : 0.0, range.sum, n);
    r.add("summedFaces", n, false);
    r.add(spec.count_key, size_of(range.below));
    if (!range.below.empty())
        r.failure = spec.failure;
    r.add_set(spec.set, MeshSet::Kind::face, std::move(range.below), spec.description);
    return r;
}

//! The edge alignment verdict, count and set (of the edges' points) into r.
void add_edge_alignment(const std::vector<Edge>& non_aligned, CheckResult& r)
{
    r.add("nonAlignedEdges", size_of(non_aligned), false);
    if (non_aligned.empty())
        return;
    r.failure = "edgeAlignment";
    std::vector<Index> points;
    for (const Edge& e : non_aligned)
    {
        points.push_back(e.first);
        points.push_back(e.second);
    }
    r.add_set("nonAlignedEdges", MeshSet::Kind::point, std::move(points),
              "points on non-aligned edges");
}

} // namespace

CheckResult check_edge_alignment(const std::vector<Edge>& non_aligned)
{
    CheckResult r(CheckId::edge_alignment);
    add_edge_alignment(non_aligned, r);
    return r;
}

CheckResult check_wedges(const PolyMesh& mesh, const std::vector<WedgeGeometry>& wedges,
                         const WedgeFindings& found)
{
    using Problem = WedgeFindings::Problem;
    CheckResult r(CheckId::wedges);
    Statistic::Reals angles;
    for (std::size_t i = 0; i < found.n_examined; ++i)
        angles.emplace_back(mesh.patches[static_cast<std::size_t>(wedges[i].patch)].name,
                            detail::rad_to_deg(std::acos(wedges[i].cos_angle)));
    r.add("wedgeAngles", std::move(angles));
    switch (found.problem)
    {
    case Problem::none:
        add_edge_alignment(found.non_aligned, r);
        break;
    case Problem::no_opposite:
        r.failure = "wedgeOpposite";
        break;
    case Problem::different_axes:
        r.failure = "wedgeAxes";
        r.add("wedgeAxis", wedges[found.n_examined - 1].axis, false);
        r.add("oppositeWedgeAxis", found.opposite_axis, false);
        break;
    case Problem::not_planar:
        r.failure = "wedgePlanarity";
        r.add("offPlanePoint", found.off_plane_point, false);
        r.add("offPlaneDistance", found.off_plane_distance, false);
        break;
    }
    return r;
}

CheckResult check_closed_boundary(const Vector3& openness)
{
    CheckResult r(CheckId::closed_boundary);
    r.add("boundaryOpenness", openness);
    if (std::max({std::abs(openness.x()), std::abs(openness.y()), std::abs(openness.z())}) > 1e-6)
        r.failure = "boundaryOpenness";
    return r;
}

CheckResult check_closed_cells(const Eigen::VectorXd& openness, const Eigen::VectorXd& aspect)
{
    const Index n_cells = static_cast<Index>(openness.size());
    double max_open = n_cells > 0 ? openness[0] : 0;
    double max_ar = n_cells > 0 ? aspect[0] : 0;
    std::vector<Index> open_cells, aspect_cells;
    for (Index cell = 0; cell < n_cells; ++cell)
    {
        max_open = std::max(max_open, openness[cell]);
        max_ar = std::max(max_ar, aspect[cell]);
        if (openness[cell] > 1e-6)
            open_cells.push_back(cell);
        if (aspect[cell] > 1000)
            aspect_cells.push_back(cell);
    }
    CheckResult r(CheckId::closed_cells);
    r.add("maxCellOpenness", max_open);
    r.add("maxAspectRatio", max_ar);
    r.add("highAspectRatioCells", size_of(aspect_cells));
    r.add("openCells", size_of(open_cells), false);
    if (!open_cells.empty())
        r.failure = "cellOpenness";
    else if (!aspect_cells.empty())
        r.failure = "aspectRatio";
    r.add_set("nonClosedCells", MeshSet::Kind::cell, std::move(open_cells), "non closed cells");
    r.add_set("highAspectRatioCells", MeshSet::Kind::cell, std::move(aspect_cells),
              "cells with high aspect ratio");
    return r;
}

CheckResult check_face_areas(const Eigen::VectorXd& mag_area)
{
    FieldRange range = field_range(mag_area, vsmall);
    CheckResult r(CheckId::face_areas);
    r.add("minFaceArea", range.min);
    r.add("maxFaceArea", range.max);
    if (range.min < vsmall)
        r.failure = "faceAreas";
    r.add_set("zeroAreaFaces", MeshSet::Kind::face, std::move(range.below), "zero area faces");
    return r;
}

CheckResult check_cell_volumes(const Eigen::VectorXd& volumes)
{
    FieldRange range = field_range(volumes, vsmall);
    CheckResult r(CheckId::cell_volumes);
    r.add("minVolume", range.min);
    r.add("maxVolume", range.max);
    r.add("totalVolume", range.sum);
    r.add("negativeVolumeCells", size_of(range.below));
    if (!range.below.empty())
        r.failure = "cellVolumes";
    r.add_set("zeroVolumeCells", MeshSet::Kind::cell, std::move(range.below), "zero volume cells");
    return r;
}

CheckResult check_face_orthogonality(const Eigen::VectorXd& ortho, const std::vector<char>& summed)
{
    const double threshold = std::cos(detail::deg_to_rad(70.0));
    Index severe = 0, errors = 0;
    const std::vector<Index> faces =
        faces_where(Index(ortho.size()), [&](Index f) { return ortho[f] < threshold; });
    for (Index f : faces)
        (ortho[f] > small ? severe : errors)++;
    // The sum in storage order (as checkMesh's); min and count without a branch per face
    // (a face not summed adds +0, which leaves every sum as it was).
    Index n_summed = 0;
    double min_cos = great, sum_cos = 0;
    for (Index f = 0; f < static_cast<Index>(ortho.size()); ++f)
    {
        const bool in = summed[static_cast<std::size_t>(f)] != 0;
        const double o = ortho[f];
        min_cos = std::min(min_cos, in ? o : great);
        sum_cos += in ? o : 0.0;
        n_summed += in;
    }
    const double avg_cos = sum_cos / static_cast<double>(std::max<Index>(n_summed, 1));
    CheckResult r(CheckId::face_orthogonality);
    r.add("maxNonOrthogonality", n_summed > 0 ? non_orthogonality_degrees(min_cos) : 0.0);
    // The parts are of the cosines: the average angle is that of the average cosine.
    r.add_average("avgNonOrthogonality", n_summed > 0 ? non_orthogonality_degrees(avg_cos) : 0.0,
                  sum_cos, n_summed);
    r.add("summedFaces", n_summed, false);
    r.add("severelyNonOrthogonalFaces", severe);
    r.add("nonOrthogonalityErrors", errors);
    if (errors > 0)
        r.failure = "nonOrthogonality";
    r.add_set("nonOrthoFaces", MeshSet::Kind::face, std::move(faces), "non-orthogonal faces");
    return r;
}

CheckResult check_face_pyramids(const std::vector<char>& errors)
{
    auto [total, faces] = error_faces(errors);
    CheckResult r(CheckId::face_pyramids);
    r.add("incorrectlyOrientedFacePyramids", total);
    if (total > 0)
        r.failure = "facePyramids";
    r.add_set("wrongOrientedFaces", MeshSet::Kind::face, std::move(faces),
              "faces with incorrect orientation");
    return r;
}

CheckResult check_face_skewness(const Eigen::VectorXd& skewness, const std::vector<char>& counted)
{
    double max_skew = skewness.size() > 0 ? skewness[0] : 0; // a maximum: any order
    const std::int64_t n = skewness.size();
#pragma omp parallel for schedule(dynamic, detail::loop_piece)                                     \
    reduction(max                                                                                  \
              : max_skew) if (n > 65536)
    for (std::int64_t f = 0; f < n; ++f)
        max_skew = std::max(max_skew, skewness[f]);
    const std::vector<Index> faces =
        faces_where(Index(n), [&](Index f) { return skewness[f] > highly_skewed_face; });
    Index n_counted = 0;
    for (Index f : faces)
        n_counted += counted.empty() || counted[static_cast<std::size_t>(f)];
    CheckResult r(CheckId::face_skewness);
    r.add("maxSkewness", max_skew);
    r.add("highlySkewedFaces", n_counted);
    if (!faces.empty())
        r.failure = "skewness";
    r.add_set("skewFaces", MeshSet::Kind::face, std::move(faces), "skew faces");
    return r;
}

CheckResult check_coupled_points(const CoupledPointMatch& match)
{
    CheckResult r(CheckId::coupled_points);
    r.add("averageCoupledMismatch", match.average_mismatch);
    r.add("mismatchedCoupledFaces", size_of(match.mismatched_faces));
    if (!match.mismatched_faces.empty())
        r.failure = "coupledPoints";
    r.add_set("coupledFaces", MeshSet::Kind::face, match.mismatched_faces,
              "faces with incorrectly matched 0th (or consecutive) vertex");
    return r;
}

CheckResult check_face_tets(const std::vector<char>& errors)
{
    auto [total, faces] = error_faces(errors);
    CheckResult r(CheckId::face_tets);
    r.add("faceTetErrors", total);
    if (total > 0)
        r.failure = "faceTets";
    r.add_set("lowQualityTetFaces", MeshSet::Kind::face, std::move(faces),
              "faces with low quality or negative volume decomposition tets");
    return r;
}

CheckResult check_edge_length(const EdgeLengths& lengths, const std::vector<char>& near,
                              double min_length_sqr)
{
    CheckResult r(CheckId::edge_length);
    r.add("minEdgeLength", lengths.min_length);
    r.add("maxEdgeLength", lengths.max_length);
    r.add("shortEdges", lengths.n_short, false);
    r.add("nearPointDistance", std::sqrt(min_length_sqr), false);
    r.add_set("shortEdges", MeshSet::Kind::point, flagged(lengths.short_edge_points),
              "points on short edges");
    // checkGeometry.C: checkPointNearness adds to the shortEdges set; the union is written
    // as nearPoints when it grew.
    std::vector<char> both = lengths.short_edge_points;
    for (std::size_t p = 0; p < near.size() && p < both.size(); ++p)
        both[p] = both[p] || near[p];
    std::vector<Index> union_labels = flagged(both);
    if (size_of(union_labels) > lengths.n_short)
        r.add_set("nearPoints", MeshSet::Kind::point, std::move(union_labels), "");
    return r;
}

CheckResult check_face_angles(const Eigen::VectorXd& concavity)
{
    double max_sin = 0;
    std::vector<Index> faces;
    for (Eigen::Index f = 0; f < concavity.size(); ++f)
    {
        max_sin = std::max(max_sin, concavity[f]);
        if (concavity[f] > small)
            faces.push_back(static_cast<Index>(f));
    }
    CheckResult r(CheckId::face_angles);
    r.add("concaveFaces", size_of(faces));
    r.add("maxConcaveAngle", detail::rad_to_deg(std::asin(std::min(1.0, max_sin))));
    r.add_set("concaveFaces", MeshSet::Kind::face, std::move(faces), "faces with concave angles");
    return r;
}

CheckResult check_face_flatness(const PolyMesh& mesh, const Eigen::VectorXd& mag_area,
                                const Eigen::VectorXd& flatness)
{
    double min_flat = great, sum_flat = 0;
    Index n_summed = 0;
    std::vector<Index> faces;
    for (Index f = 0; f < mesh.n_faces(); ++f)
        if (mesh.faces.item_size(f) > 3 && mag_area[f] > vsmall)
        {
            sum_flat += flatness[f];
            ++n_summed;
            min_flat = std::min(min_flat, flatness[f]);
            if (flatness[f] < 0.8)
                faces.push_back(f);
        }
    CheckResult r(CheckId::face_flatness);
    r.add("minFaceFlatness", n_summed > 0 ? min_flat : 1.0);
    r.add("warpedFaces", size_of(faces));
    r.add_average("avgFaceFlatness", n_summed > 0 ? sum_flat / n_summed : 1.0, sum_flat, n_summed,
                  false);
    r.add("flatnessFaces", n_summed, false);
    r.add_set("warpedFaces", MeshSet::Kind::face, std::move(faces), "warped faces");
    return r;
}

CheckResult check_cell_determinant(const Eigen::VectorXd& det)
{
    const Index n_cells = static_cast<Index>(det.size());
    double min_det = n_cells > 0 ? det[0] : 0, sum_det = 0;
    std::vector<Index> cells;
    for (Index cell = 0; cell < n_cells; ++cell)
    {
        min_det = std::min(min_det, det[cell]);
        sum_det += det[cell];
        if (det[cell] < 1e-3)
            cells.push_back(cell);
    }
    CheckResult r(CheckId::cell_determinant);
    r.add("minDeterminant", min_det);
    r.add_average("avgDeterminant", n_cells > 0 ? sum_det / n_cells : 0.0, sum_det, n_cells);
    r.add("smallDeterminantCells", size_of(cells));
    if (!cells.empty())
        r.failure = "cellDeterminant";
    r.add_set("underdeterminedCells", MeshSet::Kind::cell, std::move(cells),
              "under-determined cells");
    return r;
}

CheckResult check_concave_cells(const std::vector<char>& concave)
{
    std::vector<Index> cells = flagged(concave);
    CheckResult r(CheckId::concave_cells);
    r.add("concaveCells", size_of(cells));
    if (!cells.empty())
        r.failure = "concaveCells";
    r.add_set("concaveCells", MeshSet::Kind::cell, std::move(cells), "concave cells");
    return r;
}

CheckResult check_face_weight(const Eigen::VectorXd& weights, const std::vector<char>& summed)
{
    return check_low_values({CheckId::face_weight, "minFaceWeight", "avgFaceWeight",
                             "lowWeightFaces", 0.05, "faceWeight", "lowWeightFaces",
                             "faces with low interpolation weights"},
                            weights, summed);
}

CheckResult check_volume_ratio(const Eigen::VectorXd& ratios, const std::vector<char>& summed)
{
    return check_low_values({CheckId::volume_ratio, "minVolumeRatio", "avgVolumeRatio",
                             "lowVolumeRatioFaces", 0.01, "volumeRatio", "lowVolRatioFaces",
                             "faces with low volume ratio cells"},
                            ratios, summed);
}

} // namespace meshmorph
