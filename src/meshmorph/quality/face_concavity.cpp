// SPDX-License-Identifier: GPL-3.0-or-later
// Concave face corners in OpenFOAM's operation order.
#include "meshmorph/quality/face_concavity.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

//! The corner between the raw edges prev = p[i] - p[i-1] and next = p[i+1] - p[i]: the sin
//! of its turning angle when the corner is concave (unit cross product against the face
//! normal below SMALL) and turns by at least min_sin, else -1. Edges are normalised with
//! `eps` added to their length: ROOTVSMALL in checkMesh, VSMALL in snappyHexMesh.
double concave_corner_sin(const FoamVector& prev, const FoamVector& next, const FoamVector& normal,
                          double min_sin, double eps)
{
    const double mag_prev = detail::mag(prev);
    const FoamVector e_prev = prev / (mag_prev + eps);
    const double mag_next = detail::mag(next);
    const FoamVector e_next = next / (mag_next + eps);
    if (!(mag_prev > constants::small && mag_next > constants::small))
        return -1;
    FoamVector w = detail::cross(e_prev, e_next);
    const double mag_w = detail::mag(w);
    if (!(mag_w >= min_sin))
        return -1;
    w /= mag_w;
    return detail::dot(w, normal) < constants::small ? mag_w : -1;
}

//! Calls corner(prev, next, normal) for each corner of face f in order until it returns
//! true; the normal is the unit face area vector (eps added to its length).
template <typename Corner>
void for_each_corner(const PolyMesh& mesh, const MeshGeometry& g, Index f, double eps,
                     Corner&& corner)
{
    const std::span<const Index> face = mesh.faces[f];
    if (face.empty())
        return;
    FoamVector normal = row(g.face_areas, f);
    normal /= detail::mag(normal) + eps;
    FoamVector prev = row(mesh.points, face.front()) - row(mesh.points, face.back());
    for (std::size_t i = 0; i < face.size(); ++i)
    {
        const FoamVector next =
            row(mesh.points, face[(i + 1) % face.size()]) - row(mesh.points, face[i]);
        if (corner(prev, next, normal))
            return;
        prev = next;
    }
}

double max_concave_sin(const PolyMesh& mesh, const MeshGeometry& g, Index f, double min_sin)
{
    double max_sin = 0;
    for_each_corner(
        mesh, g, f, constants::rootvsmall,
        [&](const FoamVector& prev, const FoamVector& next, const FoamVector& normal)
        {
            // Shortcut (no sqrt/division): (prev ^ next) & normal > |prev ^ next|/2
            // (with margin) is a convex corner: the normalised cross product is
            // the same vector scaled by a positive factor, so its dot with the
            // normal is > 1/2 up to rounding (~1e-14 when it is >= sin 10 deg,
            // |normal| <= 1), far above SMALL: never counted. Every other corner
            // takes checkMesh's exact path.
            const FoamVector w_raw = detail::cross(prev, next);
            const double d_raw = detail::dot(w_raw, normal);
            if (!(d_raw > 0 && d_raw * d_raw > 0.25 * (1 + 1e-9) * detail::mag_sqr(w_raw)))
                max_sin = std::max(max_sin, concave_corner_sin(prev, next, normal, min_sin,
                                                               constants::rootvsmall));
            return false;
        });
    return max_sin;
}

} // namespace

Eigen::VectorXd face_concavity(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_faces = mesh.n_faces();
    const double min_sin = std::sin(detail::deg_to_rad(10.0));
    Eigen::VectorXd concavity(n_faces);
#pragma omp parallel for schedule(dynamic,                                                         \
                                  detail::loop_piece) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
        concavity[f] = max_concave_sin(mesh, g, f, min_sin);
    return concavity;
}

std::vector<char> faces_concave_beyond(const PolyMesh& mesh, const MeshGeometry& g, double max_sin)
{
    const Index n_faces = mesh.n_faces();
    std::vector<char> flags(static_cast<std::size_t>(n_faces), 0);
#pragma omp parallel for schedule(dynamic,                                                         \
                                  detail::loop_piece) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
        for_each_corner(
            mesh, g, f, constants::vsmall,
            [&](const FoamVector& prev, const FoamVector& next, const FoamVector& normal)
            {
                const bool concave =
                    concave_corner_sin(prev, next, normal, max_sin, constants::vsmall) >= 0;
                flags[f] = concave;
                return concave;
            });
    return flags;
}

} // namespace meshmorph
