// SPDX-License-Identifier: GPL-3.0-or-later
// checkMesh's driver (OpenFOAM v1912 checkMesh.C, checkTopology.C, checkGeometry.C): mesh
// statistics, then the topology, geometry and meshQuality checks in checkMesh's order, then
// the report. See docs/checkmesh-spec.md for every formula and line.
//
// Parallelism: the metric functions compute per-face and per-cell fields with OpenMP; the
// checks reduce them serially in storage order, so the report does not depend on the number
// of threads (nor on the schedule).
#include "meshmorph/quality/check_mesh.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/foam_vector.h"
#include "meshmorph/mesh/point_faces.h"
#include "meshmorph/quality/cell_closedness.h"
#include "meshmorph/quality/cell_concavity.h"
#include "meshmorph/quality/cell_determinant.h"
#include "meshmorph/quality/cell_regions.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/coupled_points.h"
#include "meshmorph/quality/face_concavity.h"
#include "meshmorph/quality/face_flatness.h"
#include "meshmorph/quality/face_orthogonality.h"
#include "meshmorph/quality/face_skewness.h"
#include "meshmorph/quality/face_tets.h"
#include "meshmorph/quality/face_weights.h"
#include "meshmorph/quality/geometry_checks.h"
#include "meshmorph/quality/mesh_quality_checks.h"
#include "meshmorph/quality/point_nearness.h"
#include "meshmorph/quality/processor_regions.h"
#include "meshmorph/quality/report_text.h"
#include "meshmorph/quality/scaled_jacobian.h"
#include "meshmorph/quality/topology_checks.h"

namespace meshmorph
{

namespace
{

void validate(const PolyMesh& mesh)
{
    const Index n_points = mesh.n_points();
    for (Index f = 0; f < mesh.n_faces(); ++f)
        for (Index p : mesh.faces[f])
            if (p < 0 || p >= n_points)
                throw InvalidInput("face " + std::to_string(f) + " has vertex label " +
                                   std::to_string(p) + " outside [0, " + std::to_string(n_points) +
                                   ")");
    if (static_cast<Index>(mesh.owner.size()) != mesh.n_faces())
        throw InvalidInput("owner has " + std::to_string(mesh.owner.size()) + " entries for " +
                           std::to_string(mesh.n_faces()) + " faces");
    if (mesh.n_internal_faces() > mesh.n_faces())
        throw InvalidInput("more neighbour entries than faces");
    for (Index cell : mesh.owner)
        if (cell < 0 || cell >= mesh.n_cells)
            throw InvalidInput("owner label " + std::to_string(cell) + " outside [0, nCells)");
    for (Index cell : mesh.neighbour)
        if (cell < 0 || cell >= mesh.n_cells)
            throw InvalidInput("neighbour label " + std::to_string(cell) + " outside [0, nCells)");
}

//! The number of internal points when the boundary points come last (-1 otherwise).
Index ordered_internal_points(const std::vector<char>& boundary)
{
    const Index n_points = static_cast<Index>(boundary.size());
    const Index n_internal =
        n_points - static_cast<Index>(std::count(boundary.begin(), boundary.end(), 1));
    for (Index p = n_internal; p < n_points; ++p)
        if (!boundary[p])
            return -1;
    return n_internal;
}

//! "Mesh stats" and the cell types; returns the cell shapes (for the scaled Jacobian).
std::vector<CellShape> mesh_stats(const PolyMesh& mesh, const CompactList& cell_faces,
                                  const CompactList& point_faces, bool all_topology,
                                  QualityReport& r)
{
    r.n_points = mesh.n_points();
    r.n_faces = mesh.n_faces();
    r.n_internal_faces = mesh.n_internal_faces();
    r.n_cells = mesh.n_cells;
    r.n_patches = static_cast<Index>(mesh.patches.size());
    r.n_point_zones = static_cast<Index>(mesh.point_zones.size());
    r.n_face_zones = static_cast<Index>(mesh.face_zones.size());
    r.n_cell_zones = static_cast<Index>(mesh.cell_zones.size());
    const std::vector<char> boundary = boundary_point_mask(mesh);
    r.n_internal_points = ordered_internal_points(boundary);
    if (all_topology && r.n_internal_points >= 0)
        r.edges = count_edges(mesh, point_faces, boundary);
    std::vector<CellShape> shapes = classify_cells(mesh, cell_faces);
    r.cell_types = count_cell_shapes(shapes, cell_faces);
    return shapes;
}

//! The minimum scaled Jacobian over the cells where it is defined (NaN if none).
double min_finite(const Eigen::VectorXd& values)
{
    double min = std::numeric_limits<double>::quiet_NaN();
    for (Eigen::Index i = 0; i < values.size(); ++i)
        if (std::isfinite(values[i]) && !(std::isfinite(min) && min <= values[i]))
            min = values[i];
    return min;
}

//! The points checkMesh collects in nonManifoldPoints. checkMesh -parallel (v1912) checks
//! only the patches' addressing and collects none.
std::vector<Index> non_manifold_points(const QualityReport& r, bool parallel_run)
{
    std::vector<Index> points;
    if (parallel_run)
        return points;
    for (const auto* rows : {&r.patch_topology, &r.face_zone_topology})
        for (const SurfaceTopology& s : *rows)
        {
            points.insert(points.end(), s.edge_points.begin(), s.edge_points.end());
            points.insert(points.end(), s.fan_points.begin(), s.fan_points.end());
        }
    return as_set(std::move(points));
}

//! The cell regions; in a -parallel run, joined across processor faces.
std::vector<std::vector<Index>> regions_of(const PolyMesh& mesh, const ProcessorFaces* processors)
{
    std::vector<std::vector<Index>> regions = cell_regions(mesh);
    return processors ? global_cell_regions(mesh, regions, *processors) : regions;
}

void run_topology_checks(const PolyMesh& mesh, const CompactList& cell_faces, const MeshGeometry& g,
                         const CompactList& point_faces, bool all_topology,
                         const ProcessorFaces* processors, QualityReport& r)
{
    std::vector<CheckResult>& checks = r.checks;
    checks.push_back(check_boundary_definition(mesh));
    checks.push_back(check_empty_patches(mesh));
    checks.push_back(check_cell_addressing(mesh, cell_faces));
    checks.push_back(check_point_usage(mesh));
    checks.push_back(check_upper_triangular(mesh, cell_faces));
    checks.push_back(check_face_vertices(mesh));
    if (all_topology)
    {
        checks.push_back(check_cells_zip_up(cell_edge_usage(mesh, cell_faces)));
        checks.push_back(check_face_faces(face_face_connectivity(mesh, point_faces)));
        checks.push_back(check_internal_face_cells(mesh, processors));
    }
    const std::vector<std::vector<Index>> regions = regions_of(mesh, processors);
    checks.push_back(check_regions(mesh, regions, all_topology));
    if (regions.size() > 1)
        r.cell_to_region = region_of_cells(regions, mesh.n_cells);
    r.patch_topology = patch_topology(mesh);
    r.face_zone_topology = face_zone_topology(mesh);
    r.non_manifold_points = non_manifold_points(r, processors != nullptr);
    r.non_manifold_total = size_of(r.non_manifold_points);
    r.n_topology_checks = Index(checks.size());
    r.cell_zones = cell_zone_summaries(mesh, cell_faces, g);
}

//! The mesh statistics, cell types and topology part of `before`, a report of the same
//! faces, cells and zones (whose label checks, validate(), passed): only the zones'
//! geometric summaries are recomputed.
void reuse_topology(const QualityReport& before, const PolyMesh& mesh,
                    const CompactList& cell_faces, const MeshGeometry& g, QualityReport& r)
{
    r.n_points = before.n_points;
    r.n_faces = before.n_faces;
    r.n_internal_faces = before.n_internal_faces;
    r.n_cells = before.n_cells;
    r.n_patches = before.n_patches;
    r.n_point_zones = before.n_point_zones;
    r.n_face_zones = before.n_face_zones;
    r.n_cell_zones = before.n_cell_zones;
    r.n_internal_points = before.n_internal_points;
    r.edges = before.edges;
    r.cell_types = before.cell_types;
    r.checks.assign(before.checks.begin(), before.checks.begin() + before.n_topology_checks);
    r.n_topology_checks = before.n_topology_checks;
    r.cell_to_region = before.cell_to_region;
    r.patch_topology = before.patch_topology;
    r.face_zone_topology = before.face_zone_topology;
    r.non_manifold_points = before.non_manifold_points;
    r.non_manifold_total = before.non_manifold_total;
    r.cell_zones = cell_zone_summaries(mesh, cell_faces, g);
}

//! Whether `before` can stand for this check's topology part (and its mesh statistics).
bool can_reuse_topology(const CheckMeshSettings& s, const ProcessorFaces* processors,
                        const PolyMesh& mesh)
{
    const QualityReport* before = s.unchanged_topology;
    return !s.no_topology && before != nullptr && processors == nullptr && !s.all_topology &&
           before->n_topology_checks > 0 && before->n_cells == mesh.n_cells &&
           before->n_faces == mesh.n_faces() && before->n_points == mesh.n_points();
}

//! The scaled Jacobian's corners of the check `unchanged_topology` names, when it has them
//! for this mesh's cells; else null.
std::shared_ptr<const JacobianCorners> reusable_corners(const CheckMeshSettings& s,
                                                        const PolyMesh& mesh)
{
    const QualityReport* before = s.unchanged_topology;
    if (before == nullptr || !before->jacobian_corners ||
        Index(before->jacobian_corners->types.size()) != mesh.n_cells)
        return nullptr;
    return before->jacobian_corners;
}

//! The domain's bounding box; in a -parallel run, of every rank's points.
void bounding_box(const PolyMesh& mesh, const parallel::Communicator* comm, QualityReport& r)
{
    const Index n_points = comm ? comm->sum(std::int64_t{mesh.n_points()}) : mesh.n_points();
    if (n_points == 0)
        return; // (0 0 0) (0 0 0)
    r.bounding_box_min = Eigen::Vector3d::Constant(constants::vgreat);
    r.bounding_box_max = Eigen::Vector3d::Constant(-constants::vgreat);
    for (Index p = 0; p < mesh.n_points(); ++p)
        for (int k = 0; k < 3; ++k)
        {
            r.bounding_box_min[k] = std::min(r.bounding_box_min[k], mesh.points(p, k));
            r.bounding_box_max[k] = std::max(r.bounding_box_max[k], mesh.points(p, k));
        }
    if (comm)
        for (int k = 0; k < 3; ++k)
        {
            r.bounding_box_min[k] = comm->min(r.bounding_box_min[k]);
            r.bounding_box_max[k] = comm->max(r.bounding_box_max[k]);
        }
}

void run_all_geometry_checks(const PolyMesh& mesh, const CompactList& cell_faces,
                             const MeshGeometry& g, const Eigen::VectorXd& mag_area,
                             const CoupledFaces& coupled, QualityReport& r)
{
    const Eigen::Vector3d& lo = r.bounding_box_min;
    const Eigen::Vector3d& hi = r.bounding_box_max;
    const detail::FoamVector span{hi.x() - lo.x(), hi.y() - lo.y(), hi.z() - lo.z()};
    const double min_length_sqr = detail::mag_sqr(1e-6 * span);
    std::vector<CheckResult>& checks = r.checks;
    checks.push_back(check_face_tets(face_tet_errors(mesh, g)));
    checks.push_back(check_edge_length(edge_lengths(mesh, min_length_sqr),
                                       near_points(mesh, min_length_sqr), min_length_sqr));
    checks.push_back(check_face_angles(face_concavity(mesh, g)));
    checks.push_back(check_face_flatness(mesh, mag_area, face_flatness(mesh, g, mag_area)));
    checks.push_back(check_cell_determinant(r.cell_determinant));
    checks.push_back(check_concave_cells(concave_cells(mesh, cell_faces, g)));
    const std::vector<char> summed = coupled.statistics_faces();
    checks.push_back(check_face_weight(face_weights(mesh, g, coupled), summed));
    checks.push_back(check_volume_ratio(face_volume_ratio(mesh, g.cell_volumes, coupled), summed));
}

//! The face pyramid errors of the checked points: the caller's when it has them, else
//! computed into `computed`.
const std::vector<char>& pyramid_errors_of(const PolyMesh& mesh, const MeshGeometry& g,
                                           const CheckMeshSettings& s, std::vector<char>& computed)
{
    const std::vector<char>* known = s.face_pyramid_errors;
    if (known != nullptr && Index(known->size()) == mesh.n_faces())
        return *known;
    computed = face_pyramid_errors(mesh, g);
    return computed;
}

void run_geometry_checks(const PolyMesh& mesh, const CompactList& cell_faces, const MeshGeometry& g,
                         const CheckMeshSettings& settings, const ProcessorFaces* processors,
                         QualityReport& r)
{
    const parallel::Communicator* comm = processors ? processors->comm : nullptr;
    bounding_box(mesh, comm, r);
    const std::vector<WedgeGeometry> wedges = wedge_geometries(mesh);
    r.directions = mesh_directions(mesh, g.face_areas, wedges, comm);
    const MeshDirections& dirs = r.directions;
    std::vector<CheckResult>& checks = r.checks;
    // As checkGeometry.C: the wedge check where wedges knock out a direction the solution
    // keeps, else the plain edge alignment.
    if (dirs.n_geometric() < 3 && dirs.geometric != dirs.solution)
        checks.push_back(check_wedges(mesh, wedges, wedge_findings(mesh, wedges, dirs)));
    else if (dirs.n_geometric() < 3)
        checks.push_back(check_edge_alignment(non_aligned_edges(mesh, dirs)));
    // v1912 sums every boundary face, processor faces too (their area vectors cancel over
    // the ranks, their magnitudes do not: the openness of a parallel run is smaller).
    checks.push_back(check_closed_boundary(boundary_openness(mesh, g, comm)));
    CellClosedness closedness = cell_closedness(mesh, cell_faces, g, dirs);
    checks.push_back(check_closed_cells(closedness.openness, closedness.aspect_ratio));
    r.cell_aspect_ratio = std::move(closedness.aspect_ratio);
    const Eigen::VectorXd mag_area = face_area_magnitudes(g);
    checks.push_back(check_face_areas(mag_area));
    checks.push_back(check_cell_volumes(g.cell_volumes));
    // checkMesh measures cyclic and processor faces against the cell across them
    // (polyMeshCheck.C).
    const std::vector<CyclicPatch> cyclics = cyclic_patches(mesh, g);
    const CoupledFaces coupled = coupled_faces(mesh, g, cyclics, processors);
    const Eigen::VectorXd ortho = face_orthogonality(mesh, g, coupled);
    checks.push_back(check_face_orthogonality(ortho, coupled.statistics_faces()));
    std::vector<char> computed;
    checks.push_back(check_face_pyramids(pyramid_errors_of(mesh, g, settings, computed)));
    // Without cell fields or meshQualityDict checks only the largest skewness and the faces
    // above 4 are used: screened, most faces skip the metric's gathers of their points.
    const bool every_face = settings.cell_fields || settings.mesh_quality;
    const Eigen::VectorXd skewness =
        every_face ? face_skewness(mesh, g, coupled)
                   : screened_face_skewness(mesh, g, coupled, highly_skewed_face);
    checks.push_back(check_face_skewness(skewness, coupled.master));
    checks.push_back(check_coupled_points(coupled_point_match(mesh, g, cyclics, processors)));
    if (settings.cell_fields)
    {
        r.cell_non_orthogonality = cell_non_orthogonality(cell_faces, ortho);
        r.cell_skewness = cell_skewness(cell_faces, skewness);
    }
    if (settings.cell_fields || settings.all_geometry)
        r.cell_determinant = cell_determinant(mesh, cell_faces, g, dirs, mag_area, coupled);
    if (settings.all_geometry)
        run_all_geometry_checks(mesh, cell_faces, g, mag_area, coupled, r);
    if (settings.mesh_quality)
        checks.push_back(
            check_mesh_quality(mesh, cell_faces, g, *settings.mesh_quality, skewness, coupled));
}

} // namespace

QualityReport check_mesh(const PolyMesh& mesh, const CompactList& cell_faces,
                         const MeshGeometry& geometry, const CheckMeshSettings& settings,
                         const ProcessorFaces* processors)
{
    const bool reuse = can_reuse_topology(settings, processors, mesh);
    if (!reuse)
        validate(mesh);
    require_cell_faces_of(mesh, cell_faces);
    QualityReport report;
    const CompactList pf = settings.all_topology ? point_faces(mesh) : CompactList{};
    std::vector<CellShape> shapes;
    if (reuse)
        reuse_topology(*settings.unchanged_topology, mesh, cell_faces, geometry, report);
    else
        shapes = mesh_stats(mesh, cell_faces, pf, settings.all_topology, report);
    // The paper's measure (not a checkMesh check): minimum over cells where it is defined.
    if (settings.scaled_jacobian)
    {
        report.jacobian_corners = reusable_corners(settings, mesh);
        if (!report.jacobian_corners)
        {
            if (shapes.empty()) // taken over from the check before: not classified here
                shapes = classify_cells(mesh, cell_faces);
            report.jacobian_corners =
                std::make_shared<const JacobianCorners>(jacobian_corners(mesh, cell_faces, shapes));
        }
        report.cell_scaled_jacobian = scaled_jacobian(mesh, *report.jacobian_corners);
    }
    report.min_scaled_jacobian = min_finite(report.cell_scaled_jacobian);
    if (!reuse && !settings.no_topology)
        run_topology_checks(mesh, cell_faces, geometry, pf, settings.all_topology, processors,
                            report);
    run_geometry_checks(mesh, cell_faces, geometry, settings, processors, report);
    summarise_checks(report);
    report.text = report_text(report, settings);
    return report;
}

void require_cell_faces_of(const PolyMesh& mesh, const CompactList& cell_faces)
{
    if (cell_faces.size() != mesh.n_cells)
        throw InvalidInput("cell_faces has " + std::to_string(cell_faces.size()) +
                           " cells, the mesh " + std::to_string(mesh.n_cells));
}

QualityReport check_mesh(const PolyMesh& mesh, const CheckMeshSettings& settings)
{
    validate(mesh);
    const CompactList cf = cell_faces(mesh);
    const MeshGeometry geometry = compute_geometry(mesh, cf);
    return check_mesh(mesh, cf, geometry, settings);
}

} // namespace meshmorph
