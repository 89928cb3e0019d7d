// SPDX-License-Identifier: GPL-3.0-or-later
// Face pyramid volumes in OpenFOAM's operation order.
#include "meshmorph/quality/face_pyramids.h"

#include "meshmorph/quality/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

FacePyramidVolumes face_pyramid_volumes(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_faces = mesh.n_faces();
    const Index n_int = mesh.n_internal_faces();
    FacePyramidVolumes v{Eigen::VectorXd(n_faces), Eigen::VectorXd(n_int)};
#pragma omp parallel for schedule(static) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
    {
        const FoamVector cf = row(g.face_centres, f);
        const FoamVector af = row(g.face_areas, f);
        v.owner[f] = -((1.0 / 3.0) * detail::dot(af, row(g.cell_centres, mesh.owner[f]) - cf));
        if (f < n_int)
            v.neighbour[f] =
                (1.0 / 3.0) * detail::dot(af, row(g.cell_centres, mesh.neighbour[f]) - cf);
    }
    return v;
}

} // namespace meshmorph
