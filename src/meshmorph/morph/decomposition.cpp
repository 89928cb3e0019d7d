// SPDX-License-Identifier: GPL-3.0-or-later
// A rank's part of a decomposed mesh, and bounding boxes over every rank.
#include "meshmorph/morph/decomposition.h"

#include <algorithm>

#include "meshmorph/mesh/patch_kinds.h"
#include "meshmorph/morph/patch_assignment.h"

namespace meshmorph::morph
{

Decomposition make_decomposition(const PolyMesh& mesh, std::vector<Index> global_point,
                                 const parallel::Communicator& comm)
{
    Decomposition d{&comm, std::move(global_point), {}};
    std::vector<char> shared(static_cast<std::size_t>(mesh.n_points()), 0);
    for (const Patch& patch : mesh.patches)
        if (is_processor_patch(patch))
            for (Index p : patch_points(mesh, patch))
                shared[std::size_t(p)] = 1;
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (shared[std::size_t(p)])
            d.shared_points.push_back(p);
    return d;
}

Points bounding_corners(const Points& x, const Decomposition* decomposition)
{
    const bool global = decomposition != nullptr && decomposition->is_distributed();
    // One pass over the rows: the points are stored row by row, and a column's minCoeff()
    // strides over all of them once per coordinate and bound (six passes, ~2.5 ms on the
    // motorBike, run on the main thread three times per morph).
    double lo[3] = {constants::vgreat, constants::vgreat, constants::vgreat};
    double hi[3] = {-constants::vgreat, -constants::vgreat, -constants::vgreat};
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        for (int k = 0; k < 3; ++k)
        {
            lo[k] = std::min(lo[k], x(i, k));
            hi[k] = std::max(hi[k], x(i, k));
        }
    Points corners(2, 3);
    for (int k = 0; k < 3; ++k)
    {
        corners(0, k) = global ? decomposition->comm->min(lo[k]) : lo[k];
        corners(1, k) = global ? decomposition->comm->max(hi[k]) : hi[k];
    }
    return corners;
}

} // namespace meshmorph::morph
