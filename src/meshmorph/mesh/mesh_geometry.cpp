// SPDX-License-Identifier: GPL-3.0-or-later
// Base geometry in OpenFOAM's operation order (primitiveMeshFaceCentresAndAreas,
// primitiveMeshCellCentresAndVols of v1912).
#include "meshmorph/mesh/mesh_geometry.h"

#include <span>
#include <utility>

#include "meshmorph/mesh/foam_vector.h"
#include "meshmorph/mesh/foam_vector8.h"

namespace meshmorph
{

using detail::double8;
using detail::face_vertex8;
using detail::FoamVector;
using detail::lane;
using detail::lanes8;
using detail::row;
using detail::set_row;
using detail::Vector8;

namespace
{

//! The sums of a face's triangle fan about the mean of its n vertices
//! (primitiveMeshFaceCentresAndAreas), for one face (V = FoamVector, S = double) or eight
//! quads at once (V = Vector8, S = double8). vertex(i) gives vertex i.
template <class V, class S, class Vertex> struct FanSums
{
    V mean, sum_n{}, sum_ac{};
    S sum_a{};

    FanSums(int n, const Vertex& vertex) : mean(vertex(0))
    {
        for (int i = 1; i < n; ++i)
            mean = mean + vertex(i);
        mean = mean / double(n);
        for (int i = 0; i < n; ++i)
        {
            const V pi = vertex(i);
            const V pj = vertex((i + 1) % n);
            const V c = pi + pj + mean;
            const V t = cross(pj - pi, mean - pi);
            const S a = mag(t);
            sum_n = sum_n + t;
            sum_a += a;
            sum_ac = sum_ac + a * c;
        }
    }
};

//! A face's centre and area vector from its fan's sums (one lane's, for eight quads).
std::pair<FoamVector, FoamVector> centre_and_area_of(const FoamVector& mean,
                                                     const FoamVector& sum_n,
                                                     const FoamVector& sum_ac, double sum_a)
{
    if (sum_a < constants::rootvsmall)
        return {mean, {}};
    return {((1.0 / 3.0) * sum_ac) / sum_a, 0.5 * sum_n};
}

//! Centre and area vector of one face (primitiveMeshFaceCentresAndAreas).
std::pair<FoamVector, FoamVector> centre_and_area(const Points& p, std::span<const Index> face)
{
    const std::size_t n = face.size();
    if (n == 3)
    {
        const FoamVector p0 = row(p, face[0]), p1 = row(p, face[1]), p2 = row(p, face[2]);
        return {(1.0 / 3.0) * (p0 + p1 + p2), 0.5 * detail::cross(p1 - p0, p2 - p0)};
    }
    if (n == 0)
        return {};
    const auto vertex = [&](int i) { return row(p, face[std::size_t(i)]); };
    const FanSums<FoamVector, double, decltype(vertex)> fan(int(n), vertex);
    return centre_and_area_of(fan.mean, fan.sum_n, fan.sum_ac, fan.sum_a);
}

//! centre_and_area of eight quads at once: the same fan, lane by lane (same bits with
//! -ffp-contract=off).
void quad_centres_and_areas(const PolyMesh& mesh, const Index* faces, Points& centres,
                            Points& areas)
{
    const Vector8 p[4] = {face_vertex8(mesh, faces, 0), face_vertex8(mesh, faces, 1),
                          face_vertex8(mesh, faces, 2), face_vertex8(mesh, faces, 3)};
    const auto vertex = [&](int i) { return p[i]; };
    const FanSums<Vector8, double8, decltype(vertex)> fan(4, vertex);
    for (int l = 0; l < lanes8; ++l)
    {
        const auto [centre, area] = centre_and_area_of(lane(fan.mean, l), lane(fan.sum_n, l),
                                                       lane(fan.sum_ac, l), fan.sum_a[l]);
        set_row(centres, faces[l], centre);
        set_row(areas, faces[l], area);
    }
}

} // namespace

void face_centre_and_area(const PolyMesh& mesh, Index f, Points& centres, Points& areas)
{
    const auto [centre, area] = centre_and_area(mesh.points, mesh.faces[f]);
    set_row(centres, f, centre);
    set_row(areas, f, area);
}

Vector3 face_area_vector(const PolyMesh& mesh, Index f)
{
    const FoamVector area = centre_and_area(mesh.points, mesh.faces[f]).second;
    return {area.x, area.y, area.z};
}

void face_centres_and_areas(const PolyMesh& mesh, Points& centres, Points& areas)
{
    const Index n_faces = mesh.n_faces();
    centres.resize(n_faces, 3);
    areas.resize(n_faces, 3);
    // Quads eight at a time: 94% of the motorBike's faces.
    detail::for_quads(
        n_faces, detail::parallel_threshold, [&](Index f) { return mesh.faces.item_size(f) == 4; },
        [&](const Index* quads) { quad_centres_and_areas(mesh, quads, centres, areas); },
        [&](Index f) { face_centre_and_area(mesh, f, centres, areas); });
}

void cell_centre_and_volume(const PolyMesh& mesh, const CompactList& cell_faces, Index c,
                            MeshGeometry& g)
{
    const std::span<const Index> faces = cell_faces[c];
    FoamVector estimate;
    for (Index f : faces)
        estimate += row(g.face_centres, f);
    if (!faces.empty())
        estimate /= static_cast<double>(faces.size());
    FoamVector sum_vc;
    double sum_v = 0.0;
    for (Index f : faces)
    {
        const FoamVector cf = row(g.face_centres, f);
        const FoamVector af = row(g.face_areas, f);
        const double pyr3 =
            mesh.owner[f] == c ? detail::dot(af, cf - estimate) : detail::dot(af, estimate - cf);
        const FoamVector pc = (3.0 / 4.0) * cf + (1.0 / 4.0) * estimate;
        sum_vc += pyr3 * pc;
        sum_v += pyr3;
    }
    if (std::abs(sum_v) > constants::vsmall)
        set_row(g.cell_centres, c, sum_vc / sum_v);
    else
        set_row(g.cell_centres, c, estimate);
    g.cell_volumes[c] = sum_v * (1.0 / 3.0);
}

void cell_centres_and_volumes(const PolyMesh& mesh, const CompactList& cell_faces, MeshGeometry& g)
{
    const Index n_cells = cell_faces.size();
    g.cell_centres.resize(n_cells, 3);
    g.cell_volumes.resize(n_cells);
    // One cell at a time, faces in cell_faces order: owned faces ascending, then neighboured
    // faces ascending -- the same per-cell accumulation order as OpenFOAM's owner pass
    // followed by its neighbour pass, so results are bit-identical and thread-independent.
#pragma omp parallel for schedule(dynamic, detail::loop_piece) if (mesh.n_faces() >                \
                                                                   detail::parallel_threshold)
    for (Index c = 0; c < n_cells; ++c)
        cell_centre_and_volume(mesh, cell_faces, c, g);
}

MeshGeometry compute_geometry(const PolyMesh& mesh, const CompactList& cell_faces)
{
    MeshGeometry g;
    face_centres_and_areas(mesh, g.face_centres, g.face_areas);
    cell_centres_and_volumes(mesh, cell_faces, g);
    return g;
}

MeshGeometry compute_geometry(const PolyMesh& mesh)
{
    return compute_geometry(mesh, cell_faces(mesh));
}

Eigen::VectorXd face_area_magnitudes(const MeshGeometry& g)
{
    const Index n_faces = static_cast<Index>(g.face_areas.rows());
    Eigen::VectorXd mag_area(n_faces);
#pragma omp parallel for schedule(dynamic,                                                         \
                                  detail::loop_piece) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
        mag_area[f] = detail::mag(row(g.face_areas, f));
    return mag_area;
}

MeshDirections mesh_directions(const PolyMesh& mesh, const Points& face_areas,
                               const std::vector<WedgeGeometry>& wedges,
                               const parallel::Communicator* comm)
{
    MeshDirections d;
    FoamVector empty_sum;
    bool has_empty = false;
    for (const Patch& patch : mesh.patches)
        if (patch.type == "empty" && patch.n_faces > 0)
        {
            has_empty = true;
            for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
                empty_sum += detail::cmpt_mag(row(face_areas, f));
        }
    if (comm)
    {
        has_empty = comm->any(has_empty);
        empty_sum = {comm->sum(empty_sum.x), comm->sum(empty_sum.y), comm->sum(empty_sum.z)};
    }
    if (has_empty)
    {
        const double m = detail::mag(empty_sum);
        const FoamVector unit = m > constants::vsmall ? empty_sum / m : FoamVector{};
        for (int k = 0; k < 3; ++k)
            if (unit[k] > 1e-6)
                d.solution[k] = -1;
    }
    d.geometric = d.solution;
    d.has_wedges = comm ? comm->any(!wedges.empty()) : !wedges.empty();
    if (d.has_wedges)
    {
        // The wedges' coordinate planes (centreNormal), not their tilted mean normals.
        FoamVector wedge_sum;
        for (const WedgeGeometry& w : wedges)
            wedge_sum +=
                detail::cmpt_mag({w.centre_normal.x(), w.centre_normal.y(), w.centre_normal.z()});
        if (comm)
            wedge_sum = {comm->sum(wedge_sum.x), comm->sum(wedge_sum.y), comm->sum(wedge_sum.z)};
        const double m = detail::mag(wedge_sum);
        const FoamVector unit = m >= constants::rootvsmall ? wedge_sum / m : FoamVector{};
        for (int k = 0; k < 3; ++k)
            d.geometric[k] = unit[k] > 1e-6 ? -1 : 1;
    }
    return d;
}

MeshDirections mesh_directions(const PolyMesh& mesh, const Points& face_areas)
{
    return mesh_directions(mesh, face_areas, wedge_geometries(mesh));
}

} // namespace meshmorph
