// SPDX-License-Identifier: GPL-3.0-or-later
// A variant's repair: the one-off morph's local untangling with the prescribed points held.
#include "meshmorph/design/variant_repair.h"

#include <utility>

#include "meshmorph/core/stopwatch.h"
#include "meshmorph/morph/local_untangle.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::design
{

namespace
{

//! Interior points (not on any patch, processor patches included: a point shared with
//! another rank must move alike on both) that no design variable prescribes.
std::vector<char> movable_points(const PolyMesh& mesh, const std::vector<char>& prescribed)
{
    std::vector<char> movable = boundary_point_mask(mesh);
    for (std::size_t i = 0; i < movable.size(); ++i)
        movable[i] = movable[i] || prescribed[i] ? 0 : 1;
    return movable;
}

} // namespace

VariantRepairer::VariantRepairer(PolyMesh& mesh, const CompactList& cell_faces, const Points& x0,
                                 const std::vector<char>& prescribed,
                                 const morph::Decomposition* parts)
    : cell_faces_(cell_faces), x0_(x0), parts_(parts), movable_(movable_points(mesh, prescribed))
{
    Points variant = x0; // the targets are the set-up mesh's qualities
    std::swap(mesh.points, variant);
    targets_ = morph::repair_targets(mesh, cell_faces, compute_geometry(mesh, cell_faces));
    std::swap(mesh.points, variant);
}

VariantRepair VariantRepairer::repair(PolyMesh& mesh, MeshGeometry& geometry, Index max_cells) const
{
    const Stopwatch clock;
    const parallel::Communicator& comm = parts_ != nullptr && parts_->is_distributed()
                                             ? *parts_->comm
                                             : parallel::Communicator::world();
    VariantRepair r;
    const Index to_repair = Index(comm.sum(
        std::int64_t(morph::count_cells_below_target(mesh, cell_faces_, geometry, targets_))));
    if (to_repair > max_cells)
    {
        r.skipped = "not untangled: " + std::to_string(to_repair) +
                    " cells to repair, more than maxUntangleCells " + std::to_string(max_cells) +
                    " (the local repair is for a few)";
        return r;
    }
    const morph::UntangleReport u =
        morph::untangle_cells(mesh, cell_faces_, geometry, x0_, targets_, movable_, {});
    r.tried = true;
    r.invalid_before = Index(comm.sum(std::int64_t(u.invalid_before)));
    r.invalid_after = Index(comm.sum(std::int64_t(u.invalid_after)));
    r.points_moved = Index(comm.sum(std::int64_t(u.points_moved)));
    r.max_move = comm.max(u.max_move);
    r.seconds = comm.max(clock.seconds());
    return r;
}

} // namespace meshmorph::design
