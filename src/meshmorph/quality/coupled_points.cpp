// SPDX-License-Identifier: GPL-3.0-or-later
// Coupled point matching in checkGeometry.C's order (checkCoupledPoints).
#include "meshmorph/quality/coupled_points.h"

#include <string>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/quality/foam_vector.h"

namespace meshmorph
{

CoupledPointMatch coupled_point_match(const PolyMesh& mesh, const MeshGeometry& g,
                                      const std::vector<CyclicPatch>& cyclics)
{
    CoupledPointMatch match;
    double sum = 0;
    Index n_compared = 0;
    for (const CyclicPatch& cp : cyclics)
    {
        if (!cp.owner())
            continue;
        const Patch& p = mesh.patches[static_cast<std::size_t>(cp.patch)];
        const Patch& nbr = mesh.patches[static_cast<std::size_t>(cp.neighbour)];
        const std::vector<double> tol = face_tolerances(mesh, g, p);
        for (Index i = 0; i < p.n_faces; ++i)
        {
            const std::span<const Index> face = mesh.faces[p.start_face + i];
            const std::span<const Index> other = mesh.faces[nbr.start_face + i];
            const std::size_t n = face.size();
            if (other.size() != n)
                throw InvalidInput("face " + std::to_string(p.start_face + i) + " has " +
                                   std::to_string(n) + " points, its coupled face " +
                                   std::to_string(other.size()));
            // The coupled face runs the other way round: walk this one backwards from 0.
            std::size_t fp = 0;
            for (std::size_t j = 0; j < n; ++j)
            {
                const Vector3 q = cp.transform_position(mesh.points.row(other[j]).transpose(), i);
                const double d = detail::mag(detail::row(mesh.points, face[fp]) -
                                             detail::FoamVector{q.x(), q.y(), q.z()});
                if (d > tol[static_cast<std::size_t>(i)])
                {
                    match.mismatched_faces.push_back(p.start_face + i);
                    break;
                }
                sum += d;
                ++n_compared;
                fp = fp == 0 ? n - 1 : fp - 1;
            }
        }
    }
    match.average_mismatch = n_compared > 0 ? sum / static_cast<double>(n_compared) : 0.0;
    return match;
}

} // namespace meshmorph
