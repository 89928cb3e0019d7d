// SPDX-License-Identifier: GPL-3.0-or-later
// A -parallel morph's view of the whole mesh: this rank's labels in the undecomposed mesh,
// counts over all ranks, and the distributed check (checkMeshQuality -parallel's).
#include "meshmorph/morph/distributed_case.h"

#include <algorithm>
#include <array>
#include <cstdint>

#include "meshmorph/io/decomposed_case.h"
#include "meshmorph/mesh/processor_faces.h"
#include "meshmorph/quality/check_mesh.h"
#include "meshmorph/quality/parallel_report.h"

namespace meshmorph::morph
{

//! This rank's point labels in the undecomposed mesh (decomposePar's pointProcAddressing).
Decomposition read_decomposition(const io::FoamPolyMesh& foam, const parallel::Communicator& comm)
{
    return make_decomposition(foam.mesh, io::read_point_addressing(foam), comm);
}

//! A count over the whole mesh: cells are split between the ranks; points are shared, and
//! the undecomposed mesh has (largest label + 1) of them.
Index global_count(const Decomposition& d, Index local, bool points)
{
    if (!d.is_distributed())
        return local;
    if (!points)
        return Index(d.comm->sum(std::int64_t(local)));
    return io::global_point_count(d.global_point, *d.comm);
}

//! The patches' point counts over every rank (a shared point once), for the set-up lines.
void set_global_patch_points(const PolyMesh& mesh, const Decomposition& d,
                             std::vector<PatchAssignment>& patches)
{
    std::vector<std::array<Index, 2>> mine; // (patch, global label)
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        for (Index point : patch_points(mesh, mesh.patches[p]))
            mine.push_back({Index(p), d.global_point[std::size_t(point)]});
    std::vector<Index> counts(patches.size(), 0);
    const auto gathered = d.comm->gather_values(mine); // on the master only
    if (d.comm->master())
    {
        std::vector<std::array<Index, 2>> all;
        for (const auto& rank : gathered)
            all.insert(all.end(), rank.begin(), rank.end());
        std::sort(all.begin(), all.end());
        all.erase(std::unique(all.begin(), all.end()), all.end());
        for (const auto& [patch, label] : all)
            if (std::size_t(patch) < counts.size())
                ++counts[std::size_t(patch)];
    }
    for (std::size_t p = 0; p < patches.size(); ++p)
        patches[p].n_points = counts[p];
}

namespace
{

//! The check of a -parallel run (as checkMeshQuality -parallel's): every rank checks its
//! part with the processor faces coupled; the master holds the report of the whole mesh.
//! The two counts a morph is judged by are summed on every rank, so that all refuse alike.
QualityReport distributed_check(const PolyMesh& mesh, const CompactList& cf,
                                const MeshGeometry& geometry, const CheckMeshSettings& settings,
                                const Decomposition& d)
{
    const parallel::Communicator& comm = *d.comm;
    const ProcessorFaces processors = exchange_processor_faces(mesh, geometry, comm);
    // Of a check before (a reduced report), check_mesh takes only the scaled Jacobian's
    // corners, which are this rank's (kept below): its topology part is not reused with
    // processor faces.
    const QualityReport local = check_mesh(mesh, cf, geometry, settings, &processors);
    QualityReport r = reduce_report(local, mesh, settings, processors,
                                    io::global_point_count(d.global_point, comm));
    r.jacobian_corners = local.jacobian_corners;
    r.negative_volume_cells = Index(comm.sum(std::int64_t(local.negative_volume_cells)));
    r.incorrectly_oriented_face_pyramids =
        Index(comm.sum(std::int64_t(local.incorrectly_oriented_face_pyramids)));
    return r;
}

} // namespace

//! check_mesh, or distributed_check in a -parallel run.
QualityReport check_morph_mesh(const PolyMesh& mesh, const CompactList& cf,
                               const MeshGeometry& geometry, const CheckMeshSettings& settings,
                               const Decomposition& d)
{
    return d.is_distributed() ? distributed_check(mesh, cf, geometry, settings, d)
                              : check_mesh(mesh, cf, geometry, settings);
}

} // namespace meshmorph::morph
