// SPDX-License-Identifier: GPL-3.0-or-later
// The mesh-level parts of the report (counts, cell types, patch and zone tables) travel to
// the master as JSON; the checks through reduce_check_results().
#include "meshmorph/quality/parallel_report.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "meshmorph/quality/check_reduction.h"
#include "meshmorph/quality/report_text.h"

namespace meshmorph
{

namespace
{

nlohmann::json vec(const Vector3& v)
{
    return {v.x(), v.y(), v.z()};
}

Vector3 vec(const nlohmann::json& j)
{
    return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

nlohmann::json surfaces_json(const std::vector<SurfaceTopology>& rows)
{
    nlohmann::json out = nlohmann::json::array();
    for (const SurfaceTopology& s : rows)
        out.push_back({s.n_faces, s.n_points, vec(s.bb_min), vec(s.bb_max)});
    return out;
}

nlohmann::json mesh_json(const QualityReport& r, const PolyMesh& mesh, Index processor_faces)
{
    const CellShapeCounts& c = r.cell_types;
    nlohmann::json cell_zones = nlohmann::json::array();
    for (const CellZoneSummary& z : r.cell_zones)
        cell_zones.push_back({z.n_cells, z.n_points, z.volume, vec(z.bb_min), vec(z.bb_max)});
    nlohmann::json edges = nullptr;
    if (r.edges)
        edges = {r.edges->edges, r.edges->internal_edges,
                 r.edges->internal_edges_one_boundary_point,
                 r.edges->internal_edges_two_boundary_points};
    return {{"minScaledJacobian", std::isnan(r.min_scaled_jacobian)
                                      ? nlohmann::json(nullptr)
                                      : nlohmann::json(r.min_scaled_jacobian)},
            {"counts",
             {r.n_points, r.n_faces, r.n_internal_faces, r.n_cells, r.n_internal_points,
              processor_faces, static_cast<Index>(mesh.patches.size())}},
            {"edges", edges},
            {"shapes", {c.hex, c.prism, c.wedge, c.pyramid, c.tet_wedge, c.tet, c.polyhedron}},
            {"polyhedra", c.polyhedra_by_faces},
            {"patches", surfaces_json(r.patch_topology)},
            {"faceZones", surfaces_json(r.face_zone_topology)},
            {"nonManifoldPoints", r.non_manifold_total},
            {"cellZones", cell_zones}};
}

//! Sizes summed; the bounding box over the rows that have points.
void add_surfaces(std::vector<SurfaceTopology>& rows, const nlohmann::json& other)
{
    for (std::size_t i = 0; i < rows.size() && i < other.size(); ++i)
    {
        SurfaceTopology& s = rows[i];
        const Index n_points = other[i][1].get<Index>();
        if (n_points > 0)
        {
            s.bb_min = s.n_points > 0 ? s.bb_min.cwiseMin(vec(other[i][2])) : vec(other[i][2]);
            s.bb_max = s.n_points > 0 ? s.bb_max.cwiseMax(vec(other[i][3])) : vec(other[i][3]);
        }
        s.n_faces += other[i][0].get<Index>();
        s.n_points += n_points;
        s.type.clear(); // checkMesh -parallel does not classify the surfaces
    }
}

void add_cell_zones(std::vector<CellZoneSummary>& zones, const nlohmann::json& other)
{
    for (std::size_t i = 0; i < zones.size() && i < other.size(); ++i)
    {
        CellZoneSummary& z = zones[i];
        z.n_cells += other[i][0].get<Index>();
        z.n_points += other[i][1].get<Index>();
        z.volume += other[i][2].get<double>();
        z.bb_min = z.bb_min.cwiseMin(vec(other[i][3]));
        z.bb_max = z.bb_max.cwiseMax(vec(other[i][4]));
    }
}

void add_cell_types(CellShapeCounts& c, const nlohmann::json& other)
{
    const nlohmann::json& s = other.at("shapes");
    Index* fields[] = {&c.hex, &c.prism, &c.wedge, &c.pyramid, &c.tet_wedge, &c.tet, &c.polyhedron};
    for (std::size_t k = 0; k < std::size(fields); ++k)
        *fields[k] += s[k].get<Index>();
    for (const auto& [n_faces, n] : other.at("polyhedra").get<std::map<Index, Index>>())
        c.polyhedra_by_faces[n_faces] += n;
}

void add_edges(QualityReport& r, const nlohmann::json& other)
{
    const nlohmann::json& e = other.at("edges");
    if (!r.edges || e.is_null())
    {
        r.edges.reset(); // checkMesh prints the edges only when every rank counts them
        return;
    }
    r.edges->edges += e[0].get<std::int64_t>();
    r.edges->internal_edges += e[1].get<std::int64_t>();
    r.edges->internal_edges_one_boundary_point += e[2].get<std::int64_t>();
    r.edges->internal_edges_two_boundary_points += e[3].get<std::int64_t>();
}

//! The counts of every rank: summed as checkMesh -parallel prints them, and those of the
//! undecomposed mesh (each processor face is on two ranks).
void add_counts(QualityReport& r, const nlohmann::json& other)
{
    const nlohmann::json& c = other.at("counts");
    QualityReport::ParallelStats& p = *r.parallel;
    p.summed_points += c[0].get<Index>();
    p.summed_faces += c[1].get<Index>();
    p.summed_internal_faces += c[2].get<Index>();
    r.n_cells += c[3].get<Index>();
    const Index internal_points = c[4].get<Index>();
    r.n_internal_points =
        r.n_internal_points < 0 || internal_points < 0 ? -1 : r.n_internal_points + internal_points;
    r.n_faces += c[1].get<Index>();
    r.n_internal_faces += c[2].get<Index>();
    p.processor_faces += c[5].get<Index>();
    p.min_patches = std::min(p.min_patches, c[6].get<Index>());
    p.max_patches = std::max(p.max_patches, c[6].get<Index>());
}

Index processor_face_count(const PolyMesh& mesh, const ProcessorFaces& processors)
{
    Index n = 0;
    for (const ProcessorPatch& pp : processors.patches)
        n += mesh.patches[static_cast<std::size_t>(pp.patch)].n_faces;
    return n;
}

//! The master's report with every rank's mesh-level numbers added (ranks in order).
QualityReport combine_mesh_parts(const QualityReport& local, const std::vector<std::string>& all,
                                 Index non_processor_patches, Index global_points)
{
    QualityReport r = local;
    r.parallel = QualityReport::ParallelStats{static_cast<int>(all.size())};
    r.parallel->non_processor_patches = non_processor_patches;
    r.parallel->min_patches = r.parallel->max_patches = r.n_patches;
    r.patch_topology.resize(static_cast<std::size_t>(non_processor_patches));
    r.n_cells = r.n_faces = r.n_internal_faces = 0;
    r.n_internal_points = 0;
    r.cell_types = {};
    r.non_manifold_total = 0;
    r.min_scaled_jacobian = std::numeric_limits<double>::quiet_NaN();
    r.n_patches = non_processor_patches;
    for (auto* rows : {&r.patch_topology, &r.face_zone_topology})
        for (SurfaceTopology& s : *rows)
        {
            SurfaceTopology named;
            named.name = s.name;
            s = std::move(named);
        }
    for (CellZoneSummary& z : r.cell_zones)
        z = {z.name,
             0,
             0,
             0.0,
             Vector3::Constant(constants::vgreat),
             Vector3::Constant(-constants::vgreat)};
    if (r.edges)
        r.edges = EdgeCounts{};
    for (const std::string& bytes : all)
    {
        const nlohmann::json other = nlohmann::json::from_msgpack(bytes);
        add_counts(r, other);
        if (const nlohmann::json& sj = other.at("minScaledJacobian"); !sj.is_null())
            r.min_scaled_jacobian = std::isnan(r.min_scaled_jacobian)
                                        ? sj.get<double>()
                                        : std::min(r.min_scaled_jacobian, sj.get<double>());
        add_edges(r, other);
        add_cell_types(r.cell_types, other);
        add_surfaces(r.patch_topology, other.at("patches"));
        add_surfaces(r.face_zone_topology, other.at("faceZones"));
        r.non_manifold_total += other.at("nonManifoldPoints").get<Index>();
        add_cell_zones(r.cell_zones, other.at("cellZones"));
    }
    // Each processor face is on two ranks: once a face, and an internal one.
    r.n_faces -= r.parallel->processor_faces / 2;
    r.n_internal_faces += r.parallel->processor_faces / 2;
    r.n_points = global_points;
    return r;
}

} // namespace

QualityReport reduce_report(const QualityReport& local, const PolyMesh& mesh,
                            const CheckMeshSettings& settings, const ProcessorFaces& processors,
                            Index global_points)
{
    const parallel::Communicator& comm = *processors.comm;
    const std::vector<std::uint8_t> packed =
        nlohmann::json::to_msgpack(mesh_json(local, mesh, processor_face_count(mesh, processors)));
    const std::vector<std::string> all = comm.gather(std::string(packed.begin(), packed.end()));
    std::vector<CheckResult> checks = reduce_check_results(local.checks, comm);
    if (!comm.master())
        return local;
    const Index non_processor = static_cast<Index>(mesh.patches.size() - processors.patches.size());
    QualityReport r = combine_mesh_parts(local, all, non_processor, global_points);
    r.checks = std::move(checks);
    summarise_checks(r);
    r.text = report_text(r, settings);
    return r;
}

} // namespace meshmorph
