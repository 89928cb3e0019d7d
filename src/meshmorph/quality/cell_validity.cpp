// SPDX-License-Identifier: GPL-3.0-or-later
// Negative volumes and face-pyramid orientation, in checkMesh's arithmetic.
#include "meshmorph/quality/cell_validity.h"

#include "meshmorph/quality/foam_vector.h"

namespace meshmorph
{

std::vector<char> face_pyramid_errors(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_faces = mesh.n_faces();
    const Index n_int = mesh.n_internal_faces();
    std::vector<char> n_err(static_cast<std::size_t>(n_faces), 0);
#pragma omp parallel for schedule(static) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
    {
        const detail::FoamVector cf = detail::row(g.face_centres, f);
        const detail::FoamVector af = detail::row(g.face_areas, f);
        const double own_vol =
            -((1.0 / 3.0) * detail::dot(af, detail::row(g.cell_centres, mesh.owner[f]) - cf));
        char n = own_vol < -constants::small;
        if (f < n_int)
        {
            const double nei_vol =
                (1.0 / 3.0) * detail::dot(af, detail::row(g.cell_centres, mesh.neighbour[f]) - cf);
            n += nei_vol < -constants::small;
        }
        n_err[static_cast<std::size_t>(f)] = n;
    }
    return n_err;
}

InvalidCells count_invalid_cells(const PolyMesh& mesh, const MeshGeometry& g)
{
    InvalidCells out;
    for (Eigen::Index c = 0; c < g.cell_volumes.size(); ++c)
        out.negative_volume_cells += g.cell_volumes[c] < constants::vsmall;
    for (const char e : face_pyramid_errors(mesh, g))
        out.wrong_pyramids += e;
    return out;
}

} // namespace meshmorph
