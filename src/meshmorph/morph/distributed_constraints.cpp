// SPDX-License-Identifier: GPL-3.0-or-later
// Claims gathered on the master by global point label, resolved once, sent back by rank.
#include "meshmorph/morph/distributed_constraints.h"

#include <algorithm>
#include <array>

#include "meshmorph/morph/constraint_steps.h"
#include "meshmorph/morph/cyclic_coupling.h"
#include "meshmorph/morph/handle_selection.h"
#include "meshmorph/parallel/collective.h"

namespace meshmorph::morph
{

namespace
{

//! A claim as it travels to the master.
struct WireClaim
{
    Index global = 0; //!< the point's label in the undecomposed mesh
    Index local = 0;  //!< its label on the sending rank
    Index source = 0;
    Index order = 0;
    Index rotation = -1;
    double value[3] = {0, 0, 0};
    double edge = 0.0; //!< the point's shortest boundary edge on the sending rank
    Claim::Kind kind = Claim::Kind::value;
};

//! A resolved prescription as it travels back to a rank.
struct WirePrescription
{
    Index local = 0;
    Index rotation = -1;
    double value[3] = {0, 0, 0};
    double projector[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    bool is_slip = false;
};

std::vector<WireClaim> to_wire(const std::vector<Claim>& claims, const std::vector<double>& edges,
                               const Decomposition& d)
{
    std::vector<WireClaim> out;
    out.reserve(claims.size());
    for (const Claim& c : claims)
    {
        WireClaim w;
        w.global = d.global_point[std::size_t(c.point)];
        w.local = c.point;
        w.source = c.source;
        w.order = c.order;
        w.rotation = c.rotation;
        std::copy(c.value.data(), c.value.data() + 3, w.value);
        w.edge = edges.empty() ? 0.0 : edges[std::size_t(c.point)];
        w.kind = c.kind;
        out.push_back(w);
    }
    return out;
}

//! The master's view: every point claimed anywhere, numbered compactly in the order of its
//! global label (the order of a serial run), and where each lives.
struct GlobalPoints
{
    std::vector<Index> global;                             //!< compact -> global label
    std::vector<std::vector<std::array<Index, 2>>> owners; //!< compact -> (rank, local)

    Index compact(Index label) const
    {
        return static_cast<Index>(std::lower_bound(global.begin(), global.end(), label) -
                                  global.begin());
    }
};

GlobalPoints number_points(const std::vector<std::vector<WireClaim>>& a,
                           const std::vector<std::vector<WireClaim>>& b)
{
    GlobalPoints g;
    for (const auto* all : {&a, &b})
        for (const std::vector<WireClaim>& rank : *all)
            for (const WireClaim& w : rank)
                g.global.push_back(w.global);
    std::sort(g.global.begin(), g.global.end());
    g.global.erase(std::unique(g.global.begin(), g.global.end()), g.global.end());
    g.owners.resize(g.global.size());
    for (const auto* all : {&a, &b})
        for (std::size_t r = 0; r < all->size(); ++r)
            for (const WireClaim& w : (*all)[r])
                g.owners[std::size_t(g.compact(w.global))].push_back({Index(r), w.local});
    for (auto& o : g.owners)
    {
        std::sort(o.begin(), o.end());
        o.erase(std::unique(o.begin(), o.end()), o.end());
    }
    return g;
}

//! Claims by compact point, in serial order (point, then source), each (point, source)
//! once: a shared point's claims arrive from every rank that holds it, identical.
std::vector<Claim> compact_claims(const std::vector<std::vector<WireClaim>>& all,
                                  const GlobalPoints& g, std::vector<double>* edges)
{
    std::vector<Claim> claims;
    if (edges != nullptr)
        edges->assign(g.global.size(), std::numeric_limits<double>::infinity());
    for (const std::vector<WireClaim>& rank : all)
        for (const WireClaim& w : rank)
        {
            const Index p = g.compact(w.global);
            claims.push_back({p, w.source, w.order, w.kind,
                              Vector3(w.value[0], w.value[1], w.value[2]), w.rotation});
            if (edges != nullptr)
                (*edges)[std::size_t(p)] = std::min((*edges)[std::size_t(p)], w.edge);
        }
    std::stable_sort(claims.begin(), claims.end(),
                     [](const Claim& a, const Claim& b)
                     { return a.point != b.point ? a.point < b.point : a.source < b.source; });
    claims.erase(std::unique(claims.begin(), claims.end(),
                             [](const Claim& a, const Claim& b)
                             { return a.point == b.point && a.source == b.source; }),
                 claims.end());
    return claims;
}

//! The resolved constraints (compact points) split by the ranks that hold each point.
std::vector<std::vector<WirePrescription>> split_by_rank(const Constraints& c,
                                                         const std::vector<Vector3>& values,
                                                         const GlobalPoints& g, int n_ranks)
{
    std::vector<std::vector<WirePrescription>> out(static_cast<std::size_t>(n_ranks));
    const auto send = [&](Index compact, WirePrescription w)
    {
        for (const auto& [rank, local] : g.owners[std::size_t(compact)])
        {
            w.local = local;
            out[std::size_t(rank)].push_back(w);
        }
    };
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        WirePrescription w;
        w.rotation = c.rotation_of[i];
        std::copy(values[i].data(), values[i].data() + 3, w.value);
        send(c.points[i], w);
    }
    for (std::size_t i = 0; i < c.slip_points.size(); ++i)
    {
        WirePrescription w;
        w.is_slip = true;
        std::copy(c.slip_projectors[i].data(), c.slip_projectors[i].data() + 9, w.projector);
        send(c.slip_points[i], w);
    }
    return out;
}

//! This rank's constraints from its prescriptions (sorted by local point).
void set_local(std::vector<WirePrescription> mine, Constraints& out)
{
    std::sort(mine.begin(), mine.end(),
              [](const WirePrescription& a, const WirePrescription& b)
              { return a.local < b.local; });
    out.points.clear();
    out.rotation_of.clear();
    out.slip_points.clear();
    out.slip_projectors.clear();
    std::vector<Vector3> values;
    for (const WirePrescription& w : mine)
        if (w.is_slip)
        {
            out.slip_points.push_back(w.local);
            out.slip_projectors.push_back(Eigen::Map<const Eigen::Matrix3d>(w.projector));
        }
        else
        {
            out.points.push_back(w.local);
            out.rotation_of.push_back(w.rotation);
            values.emplace_back(w.value[0], w.value[1], w.value[2]);
        }
    detail::fill_displacements(values, out);
}

//! The master's empty planes on every rank (a part may have none of its own faces).
std::optional<EmptyPlanes> agreed_empty_planes(const PolyMesh& mesh,
                                               const parallel::Communicator& comm)
{
    const std::optional<EmptyPlanes> mine = find_empty_planes(mesh);
    const std::vector<double> wire = mine ? std::vector<double>{mine->normal.x(), mine->normal.y(),
                                                                mine->normal.z(), mine->offset}
                                          : std::vector<double>{};
    const std::vector<std::vector<double>> all = comm.gather_values(wire);
    std::vector<double> chosen;
    for (const std::vector<double>& w : all)
        if (chosen.empty() && w.size() == 4)
            chosen = w;
    chosen = comm.broadcast_values(chosen);
    if (chosen.empty())
        return std::nullopt;
    return EmptyPlanes{Vector3(chosen[0], chosen[1], chosen[2]), chosen[3]};
}

} // namespace

Constraints build_distributed_constraints(const PolyMesh& mesh, const MorphSetup& setup,
                                          const ConstraintInputs& inputs,
                                          const Decomposition& decomposition)
{
    const parallel::Communicator& comm = *decomposition.comm;
    Constraints out;
    out.conflict_rule = setup.conflicts;
    out.jump_smoothing = setup.jump_smoothing;
    parallel::collective(comm,
                         [&] {
                             out.patches = inputs.patches != nullptr
                                               ? *inputs.patches
                                               : assign_patches(mesh, setup, true);
                         });
    out.empty_planes = agreed_empty_planes(mesh, comm);
    // Each rank's own wedge pairs: a cell's two wedge faces, and so both partners of its
    // points, live on one rank.
    parallel::collective(comm, [&] { out.wedge = find_wedge_symmetry(mesh); });
    const Points corners = bounding_corners(mesh.points, &decomposition);
    const double agree_tol =
        detail::agreement_tolerance(corners.row(0).transpose(), corners.row(1).transpose());

    std::vector<Claim> claims;
    parallel::collective(comm,
                         [&] {
                             claims = collect_claims(mesh, setup, out.patches, inputs,
                                                     out.empty_planes, out.rotations);
                         });
    const std::vector<Claim> handle_claims =
        collect_handle_claims(mesh, setup, out.empty_planes, agree_tol, &decomposition);
    const auto boundary_wire =
        comm.gather_values(to_wire(claims, detail::shortest_boundary_edges(mesh), decomposition));
    const auto handle_wire = comm.gather_values(to_wire(handle_claims, {}, decomposition));

    std::vector<std::vector<WirePrescription>> per_rank;
    parallel::on_master(
        comm,
        [&]
        {
            const GlobalPoints g = number_points(boundary_wire, handle_wire);
            std::vector<double> edges;
            const std::vector<Claim> all_claims = compact_claims(boundary_wire, g, &edges);
            const std::vector<Claim> all_handles = compact_claims(handle_wire, g, nullptr);
            const std::vector<Vector3> values =
                detail::resolve_and_merge(mesh, setup, all_claims, edges, all_handles, agree_tol,
                                          (corners.row(1) - corners.row(0)).norm(), out);
            per_rank = split_by_rank(out, values, g, comm.size());
            out.n_prescribed_points = static_cast<Index>(out.points.size());
            out.n_slip_points = static_cast<Index>(out.slip_points.size());
        });
    const Index prescribed = out.n_prescribed_points, slip = out.n_slip_points;
    set_local(comm.scatter_values(per_rank), out);
    // Each rank couples the cyclics it holds (whole: processorCyclic is refused). The totals
    // grow by the points coupled (a point shared by ranks counts once per rank here).
    const auto before = std::array{out.points.size(), out.slip_points.size()};
    parallel::collective(
        comm, [&] { couple_cyclic_prescriptions(mesh, cyclic_point_pairs(mesh), agree_tol, out); });
    const Index added = Index(comm.sum(std::int64_t(out.points.size() - before[0])));
    const Index unslipped = Index(comm.sum(std::int64_t(before[1] - out.slip_points.size())));
    if (comm.master()) // set_local counted this rank's points
    {
        out.n_prescribed_points = prescribed + added;
        out.n_slip_points = slip - unslipped;
    }
    return out;
}

} // namespace meshmorph::morph
