// SPDX-License-Identifier: GPL-3.0-or-later
// Face skewness in OpenFOAM's operation order.
#include "meshmorph/quality/face_skewness.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "meshmorph/mesh/foam_vector.h"
#include "meshmorph/mesh/foam_vector8.h"

namespace meshmorph
{

using detail::double8;
using detail::FoamVector;
using detail::row;
using detail::Vector8;

namespace
{

//! The skewness of a face from its centre cf, area af, the offset cpf of cf from the owner's
//! centre, the vector d it is measured along (to the cell across, or the owner centre's
//! projection onto the face normal), the normalisation factor and its n vertices, for one
//! face (V = FoamVector, S = double) or eight at once (V = Vector8, S = double8).
template <class V, class S, class Vertex>
S skewness_from(const V& cf, const V& af, const V& cpf, const V& d, double factor, int n,
                const Vertex& vertex)
{
    constexpr double rootvsmall = constants::rootvsmall;
    const V sv = cpf - (dot(af, cpf) / (dot(af, d) + rootvsmall)) * d;
    const V sv_hat = sv / (mag(sv) + rootvsmall);
    S fd = factor * mag(d) + rootvsmall;
    for (int k = 0; k < n; ++k)
        fd = detail::lane_max(fd, detail::lane_abs(dot(sv_hat, vertex(k) - cf)));
    return mag(sv) / fd;
}

//! What a face's skewness is measured with: its centre cf and area af, the offset cpf of
//! cf from the owner's centre, the vector d it is measured along and the normalisation
//! factor.
struct SkewnessFrame
{
    FoamVector cf, af, cpf, d;
    double factor;
};

//! The frame of face f; `across` is the cell centre on the other side, if any.
SkewnessFrame frame_of(const PolyMesh& mesh, const MeshGeometry& g, Index f,
                       const FoamVector* across)
{
    SkewnessFrame s;
    s.cf = row(g.face_centres, f);
    s.af = row(g.face_areas, f);
    const FoamVector own_cc = row(g.cell_centres, mesh.owner[f]);
    s.cpf = s.cf - own_cc;
    if (across)
    {
        s.d = *across - own_cc;
        s.factor = 0.2;
    }
    else
    {
        FoamVector normal = s.af;
        normal /= detail::mag(normal) + constants::rootvsmall;
        s.d = detail::dot(normal, s.cpf) * normal;
        s.factor = 0.4;
    }
    return s;
}

//! Skewness of face f; `across` is the cell centre on the other side, if any.
double skewness_of(const PolyMesh& mesh, const MeshGeometry& g, Index f, const FoamVector* across)
{
    const SkewnessFrame s = frame_of(mesh, g, f, across);
    const std::span<const Index> face = mesh.faces[f];
    return skewness_from<FoamVector, double>(s.cf, s.af, s.cpf, s.d, s.factor, int(face.size()),
                                             [&](int k)
                                             { return row(mesh.points, face[std::size_t(k)]); });
}

//! An upper bound of skewness_of without its vertices: skewness_from's denominator starts
//! at factor |d| + rootvsmall and only grows by the vertices' term, and the bound divides
//! the same |sv|, computed by the same operations, by that start (division by a larger
//! positive number never gives more, in floating point too).
double skewness_bound_of(const PolyMesh& mesh, const MeshGeometry& g, Index f,
                         const FoamVector* across)
{
    constexpr double rootvsmall = constants::rootvsmall;
    const SkewnessFrame s = frame_of(mesh, g, f, across);
    const FoamVector sv = s.cpf - (dot(s.af, s.cpf) / (dot(s.af, s.d) + rootvsmall)) * s.d;
    return mag(sv) / (s.factor * mag(s.d) + rootvsmall);
}

//! skewness_of eight internal quads at once: the same kernel, lane by lane (same bits).
void internal_quads_skewness(const PolyMesh& mesh, const MeshGeometry& g, const Index* faces,
                             Eigen::VectorXd& skewness)
{
    std::array<Index, detail::lanes8> owner, neighbour;
    for (int l = 0; l < detail::lanes8; ++l)
    {
        owner[std::size_t(l)] = mesh.owner[faces[l]];
        neighbour[std::size_t(l)] = mesh.neighbour[faces[l]];
    }
    const Vector8 cf = detail::gather8(g.face_centres, faces);
    const Vector8 own_cc = detail::gather8(g.cell_centres, owner.data());
    const double8 s = skewness_from<Vector8, double8>(
        cf, detail::gather8(g.face_areas, faces), cf - own_cc,
        detail::gather8(g.cell_centres, neighbour.data()) - own_cc, 0.2, 4,
        [&](int k) { return detail::face_vertex8(mesh, faces, k); });
    for (int l = 0; l < detail::lanes8; ++l)
        skewness[faces[l]] = s[l];
}

//! The face skewness of checkMesh (face_skewness with coupled faces) at f, or its bound.
template <class Measure>
double checkmesh_measure(const PolyMesh& mesh, const MeshGeometry& g, const CoupledFaces& coupled,
                         Index f, const Measure& measure)
{
    const Index n_int = mesh.n_internal_faces();
    if (f < n_int)
    {
        const FoamVector across = row(g.cell_centres, mesh.neighbour[f]);
        return measure(mesh, g, f, &across);
    }
    if (coupled.coupled_boundary(mesh, f))
    {
        const FoamVector across = row(coupled.neighbour_cell_centres, f - n_int);
        return measure(mesh, g, f, &across);
    }
    return measure(mesh, g, f, nullptr);
}

} // namespace

Eigen::VectorXd face_skewness(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_faces = mesh.n_faces(), n_internal = mesh.n_internal_faces();
    Eigen::VectorXd skewness(n_faces);
    detail::for_quads(
        n_faces, detail::parallel_threshold,
        [&](Index f) { return f < n_internal && mesh.faces.item_size(f) == 4; },
        [&](const Index* quads) { internal_quads_skewness(mesh, g, quads, skewness); },
        [&](Index f) { skewness[f] = face_skewness_at(mesh, g, f); });
    return skewness;
}

double face_skewness_at(const PolyMesh& mesh, const MeshGeometry& g, Index f)
{
    if (f >= mesh.n_internal_faces())
        return skewness_of(mesh, g, f, nullptr);
    const FoamVector across = row(g.cell_centres, mesh.neighbour[f]);
    return skewness_of(mesh, g, f, &across);
}

Eigen::VectorXd face_skewness(const PolyMesh& mesh, const MeshGeometry& g,
                              const CoupledFaces& coupled)
{
    Eigen::VectorXd skewness = face_skewness(mesh, g);
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
        if (coupled.coupled_boundary(mesh, f))
            skewness[f] = checkmesh_measure(mesh, g, coupled, f, skewness_of);
    return skewness;
}

Eigen::VectorXd screened_face_skewness(const PolyMesh& mesh, const MeshGeometry& g,
                                       const CoupledFaces& coupled, double threshold)
{
    const Index n_faces = mesh.n_faces();
    Eigen::VectorXd bound(n_faces);
#pragma omp parallel for schedule(dynamic,                                                         \
                                  detail::loop_piece) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
        bound[f] = checkmesh_measure(mesh, g, coupled, f, skewness_bound_of);
    Eigen::VectorXd skewness = Eigen::VectorXd::Zero(n_faces);
    // The exact value wherever `wanted(f)`; returns the largest of them.
    const auto exact_where = [&](const auto& wanted)
    {
        double largest = 0.0;
#pragma omp parallel for schedule(dynamic, detail::loop_piece)                                     \
    reduction(max                                                                                  \
              : largest) if (n_faces > detail::parallel_threshold)
        for (Index f = 0; f < n_faces; ++f)
            if (wanted(f))
            {
                skewness[f] = checkmesh_measure(mesh, g, coupled, f, skewness_of);
                largest = std::max(largest, skewness[f]);
            }
        return largest;
    };
    // Every face whose bound exceeds the threshold (or is not finite) exact: a face left out
    // is at most the threshold.
    const double above = exact_where([&](Index f) { return !(bound[f] <= threshold); });
    if (above >= threshold || n_faces == 0)
        return skewness;
    // All faces at most the threshold: the largest is at least the value of the face with
    // the largest bound, and no face whose bound is below that can exceed it.
    Index top = 0;
    bound.maxCoeff(&top);
    skewness[top] = checkmesh_measure(mesh, g, coupled, top, skewness_of);
    const double level = std::max(above, skewness[top]);
    (void)exact_where([&](Index f) { return bound[f] > level && bound[f] <= threshold; });
    return skewness;
}

Eigen::VectorXd cell_skewness(const CompactList& cell_faces, const Eigen::VectorXd& skewness)
{
    const Index n_cells = cell_faces.size();
    Eigen::VectorXd cell(n_cells);
#pragma omp parallel for schedule(dynamic, detail::loop_piece) if (skewness.size() >               \
                                                                   detail::parallel_threshold)
    for (Index c = 0; c < n_cells; ++c)
    {
        double max_skew = 0;
        for (Index f : cell_faces[c])
            max_skew = std::max(max_skew, skewness[f]);
        cell[c] = max_skew;
    }
    return cell;
}

} // namespace meshmorph
