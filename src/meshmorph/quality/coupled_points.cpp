// SPDX-License-Identifier: GPL-3.0-or-later
// Coupled point matching in checkGeometry.C's order (checkCoupledPoints).
#include "meshmorph/quality/coupled_points.h"

#include <string>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

namespace
{

//! The running comparison: mismatched faces, the sum and number of distances compared.
struct Comparison
{
    CoupledPointMatch match;
    double sum = 0;
    Index n_compared = 0;

    //! Face f against `other` (its coupled face's points, on this side), which runs the
    //! other way round: walk f backwards from vertex 0.
    void compare(const PolyMesh& mesh, Index f, const std::vector<Vector3>& other, double tol)
    {
        const std::span<const Index> face = mesh.faces[f];
        const std::size_t n = face.size();
        if (other.size() != n)
            throw InvalidInput("face " + std::to_string(f) + " has " + std::to_string(n) +
                               " points, its coupled face " + std::to_string(other.size()));
        std::size_t fp = 0;
        for (const Vector3& q : other)
        {
            const double d = detail::mag(detail::row(mesh.points, face[fp]) -
                                         detail::FoamVector{q.x(), q.y(), q.z()});
            if (d > tol)
            {
                match.mismatched_faces.push_back(f);
                return;
            }
            sum += d;
            ++n_compared;
            fp = fp == 0 ? n - 1 : fp - 1;
        }
    }
};

void compare_cyclic(const PolyMesh& mesh, const MeshGeometry& g, const CyclicPatch& cp,
                    Comparison& c)
{
    const Patch& p = mesh.patches[static_cast<std::size_t>(cp.patch)];
    const Patch& nbr = mesh.patches[static_cast<std::size_t>(cp.neighbour)];
    const std::vector<double> tol = face_tolerances(mesh, g, p);
    for (Index i = 0; i < p.n_faces; ++i)
    {
        std::vector<Vector3> other;
        for (Index v : mesh.faces[nbr.start_face + i])
            other.push_back(cp.transform_position(mesh.points.row(v).transpose(), i));
        c.compare(mesh, p.start_face + i, other, tol[static_cast<std::size_t>(i)]);
    }
}

void compare_processor(const PolyMesh& mesh, const MeshGeometry& g,
                       const ProcessorFaces& processors, const ProcessorPatch& pp, Comparison& c)
{
    const Patch& p = mesh.patches[static_cast<std::size_t>(pp.patch)];
    const std::vector<double> tol = face_tolerances(mesh, g, p);
    for (Index i = 0; i < p.n_faces; ++i)
    {
        const Index f = p.start_face + i;
        c.compare(
            mesh, f,
            processors.neighbour_face_points[static_cast<std::size_t>(f - mesh.n_internal_faces())],
            tol[static_cast<std::size_t>(i)]);
    }
}

} // namespace

CoupledPointMatch coupled_point_match(const PolyMesh& mesh, const MeshGeometry& g,
                                      const std::vector<CyclicPatch>& cyclics,
                                      const ProcessorFaces* processors)
{
    Comparison c;
    for (const CyclicPatch& cp : cyclics)
        if (cp.owner())
            compare_cyclic(mesh, g, cp, c);
    if (processors)
        for (const ProcessorPatch& pp : processors->patches)
            if (pp.owner)
                compare_processor(mesh, g, *processors, pp, c);
    c.match.average_mismatch = c.n_compared > 0 ? c.sum / static_cast<double>(c.n_compared) : 0.0;
    return c.match;
}

} // namespace meshmorph
