// SPDX-License-Identifier: GPL-3.0-or-later
// Concave cells in OpenFOAM's operation order.
#include "meshmorph/quality/cell_concavity.h"

#include <algorithm>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

//! Whether a face centre of `faces` other than the i-th is not behind face i's plane.
bool in_front_of_face(const PolyMesh& mesh, const MeshGeometry& g, std::span<const Index> faces,
                      std::size_t i, Index cell)
{
    constexpr double vsmall = constants::vsmall;
    const Index fi = faces[i];
    const FoamVector ci = row(g.face_centres, fi);
    FoamVector n = row(g.face_areas, fi);
    n /= std::max(detail::mag(n), vsmall);
    if (mesh.owner[fi] != cell)
        n = -n;
    for (std::size_t j = 0; j < faces.size(); ++j)
    {
        if (j == i)
            continue;
        FoamVector u = row(g.face_centres, faces[j]) - ci;
        // Shortcut (no sqrt/divisions): when (u & n) / |u| < -2e-6 exactly, the rounded
        // normalised product checkMesh computes (error ~1e-15, as |u/|u|| = 1 and |n| <= 1)
        // is certainly below -1e-6, so the pair passes. Only for |u|^2 well above vsmall^2
        // and without underflow of s^2; every other pair takes OpenFOAM's exact path below.
        const double s_un = detail::dot(u, n);
        const double m2 = detail::mag_sqr(u);
        if (s_un < 0 && m2 > 1e-200 && s_un * s_un > 4e-12 * m2)
            continue;
        u /= std::max(detail::mag(u), vsmall);
        if (detail::dot(u, n) > -1e-6)
            return true;
    }
    return false;
}

} // namespace

std::vector<char> concave_cells(const PolyMesh& mesh, const CompactList& cell_faces,
                                const MeshGeometry& g)
{
    const Index n_cells = mesh.n_cells;
    std::vector<char> concave(static_cast<std::size_t>(n_cells), 0);
#pragma omp parallel for schedule(dynamic, 2048) if (mesh.n_faces() > detail::parallel_threshold)
    for (Index cell = 0; cell < n_cells; ++cell)
    {
        const std::span<const Index> faces = cell_faces[cell];
        for (std::size_t i = 0; i < faces.size() && !concave[cell]; ++i)
            concave[cell] = in_front_of_face(mesh, g, faces, i, cell);
    }
    return concave;
}

} // namespace meshmorph
