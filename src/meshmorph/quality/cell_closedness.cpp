// SPDX-License-Identifier: GPL-3.0-or-later
// Boundary and cell closedness, cell aspect ratio, in OpenFOAM's operation order.
#include "meshmorph/quality/cell_closedness.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

double openness_of(const FoamVector& sum, const FoamVector& sum_mag)
{
    double max_open = 0;
    for (int k = 0; k < 3; ++k)
        max_open = std::max(max_open, std::abs(sum[k]) / (sum_mag[k] + constants::rootvsmall));
    return max_open;
}

double aspect_ratio_of(const FoamVector& sum_mag, double volume, const MeshDirections& dirs)
{
    constexpr double rootvsmall = constants::rootvsmall;
    double min_c = constants::vgreat, max_c = -constants::vgreat;
    for (int k = 0; k < 3; ++k)
        if (dirs.geometric[k] == 1)
        {
            min_c = std::min(min_c, sum_mag[k]);
            max_c = std::max(max_c, sum_mag[k]);
        }
    double ar = max_c / (min_c + rootvsmall);
    if (dirs.n_geometric() == 3)
    {
        const double v = std::max(rootvsmall, volume);
        ar = std::max(ar, 1.0 / 6.0 * (sum_mag.x + sum_mag.y + sum_mag.z) / std::pow(v, 2.0 / 3.0));
    }
    return ar;
}

} // namespace

Vector3 boundary_openness(const PolyMesh& mesh, const MeshGeometry& g,
                          const parallel::Communicator* comm)
{
    FoamVector sum;
    double sum_mag = 0;
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
    {
        const FoamVector a = row(g.face_areas, f);
        sum += a;
        sum_mag += detail::mag(a);
    }
    if (comm)
    {
        sum = {comm->sum(sum.x), comm->sum(sum.y), comm->sum(sum.z)};
        sum_mag = comm->sum(sum_mag);
    }
    const FoamVector o = sum / (sum_mag + constants::vsmall);
    return {o.x, o.y, o.z};
}

CellClosedness cell_closedness(const PolyMesh& mesh, const CompactList& cell_faces,
                               const MeshGeometry& g, const MeshDirections& dirs)
{
    const Index n_cells = mesh.n_cells;
    CellClosedness r{Eigen::VectorXd(n_cells), Eigen::VectorXd(n_cells)};
#pragma omp parallel for schedule(dynamic, detail::loop_piece) if (mesh.n_faces() >                \
                                                                   detail::parallel_threshold)
    for (Index cell = 0; cell < n_cells; ++cell)
    {
        FoamVector sum, sum_mag;
        for (Index f : cell_faces[cell])
        {
            const FoamVector a = row(g.face_areas, f);
            if (mesh.owner[f] == cell)
                sum += a;
            else
                sum -= a;
            sum_mag += detail::cmpt_mag(a);
        }
        r.openness[cell] = openness_of(sum, sum_mag);
        r.aspect_ratio[cell] = aspect_ratio_of(sum_mag, g.cell_volumes[cell], dirs);
    }
    return r;
}

} // namespace meshmorph
