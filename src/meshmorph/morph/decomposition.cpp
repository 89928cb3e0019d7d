// SPDX-License-Identifier: GPL-3.0-or-later
// A rank's part of a decomposed mesh, and bounding boxes over every rank.
#include "meshmorph/morph/decomposition.h"

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
    Points corners(2, 3);
    for (int k = 0; k < 3; ++k)
    {
        const double lo = x.rows() > 0 ? x.col(k).minCoeff() : constants::vgreat;
        const double hi = x.rows() > 0 ? x.col(k).maxCoeff() : -constants::vgreat;
        corners(0, k) = global ? decomposition->comm->min(lo) : lo;
        corners(1, k) = global ? decomposition->comm->max(hi) : hi;
    }
    return corners;
}

} // namespace meshmorph::morph
