// SPDX-License-Identifier: GPL-3.0-or-later
// Local regions are joined on the master: each owner-side processor face links its cell's
// region to the neighbour's; the master numbers the joined regions and sends each rank the
// global number of its local ones.
#include "meshmorph/quality/processor_regions.h"

#include <algorithm>
#include <cstdint>

#include "meshmorph/quality/cell_regions.h"
#include "meshmorph/quality/check_result.h"
#include "meshmorph/quality/disjoint_sets.h"

namespace meshmorph
{

namespace
{

//! Per boundary face, the local region of its owner cell.
std::vector<double> owner_regions(const PolyMesh& mesh, const std::vector<Index>& cell_region)
{
    const Index n_int = mesh.n_internal_faces();
    std::vector<double> out(static_cast<std::size_t>(mesh.n_faces() - n_int));
    for (Index f = n_int; f < mesh.n_faces(); ++f)
        out[static_cast<std::size_t>(f - n_int)] =
            static_cast<double>(cell_region[static_cast<std::size_t>(mesh.owner[f])]);
    return out;
}

//! On the master: the global region of every (rank, local region), numbered in order.
std::vector<std::int64_t> number_regions(const std::vector<std::vector<std::int64_t>>& counts,
                                         const std::vector<std::vector<std::int64_t>>& links)
{
    std::vector<std::int64_t> offset(counts.size() + 1, 0);
    for (std::size_t r = 0; r < counts.size(); ++r)
        offset[r + 1] = offset[r] + counts[r].at(0);
    const Index total = static_cast<Index>(offset.back());
    detail::DisjointSets sets(total);
    for (std::size_t r = 0; r < links.size(); ++r)
        for (std::size_t i = 0; i + 2 < links[r].size(); i += 3)
        {
            Index a = sets.find(static_cast<Index>(offset[r] + links[r][i]));
            Index b = sets.find(static_cast<Index>(
                offset[static_cast<std::size_t>(links[r][i + 1])] + links[r][i + 2]));
            if (a != b)
                sets.link(std::max(a, b), std::min(a, b));
        }
    std::vector<std::int64_t> global(static_cast<std::size_t>(total), -1), root_number(global);
    std::int64_t next = 0;
    for (Index i = 0; i < total; ++i)
    {
        std::int64_t& n = root_number[static_cast<std::size_t>(sets.find(i))];
        if (n < 0)
            n = next++;
        global[static_cast<std::size_t>(i)] = n;
    }
    global.push_back(next); // the number of regions, last
    return global;
}

} // namespace

std::vector<std::vector<Index>> global_cell_regions(const PolyMesh& mesh,
                                                    const std::vector<std::vector<Index>>& local,
                                                    const ProcessorFaces& processors)
{
    const parallel::Communicator& comm = *processors.comm;
    const std::vector<Index> cell_region = region_of_cells(local, mesh.n_cells);
    const std::vector<double> mine = owner_regions(mesh, cell_region);
    const std::vector<double> theirs = swap_processor_values(mesh, processors, mine);
    // (local region, neighbour rank, neighbour's region) per owner-side processor face.
    std::vector<std::int64_t> links;
    for (const ProcessorPatch& pp : processors.patches)
    {
        if (!pp.owner)
            continue;
        const Patch& p = mesh.patches[static_cast<std::size_t>(pp.patch)];
        const Index first = p.start_face - mesh.n_internal_faces();
        for (Index b = first; b < first + p.n_faces; ++b)
            links.insert(links.end(), {static_cast<std::int64_t>(mine[b]), pp.neighbour_rank,
                                       static_cast<std::int64_t>(theirs[b])});
    }
    const auto counts = comm.gather_values(std::vector<std::int64_t>{size_of(local)});
    const auto all_links = comm.gather_values(links);
    std::vector<std::vector<std::int64_t>> per_rank;
    if (comm.master())
    {
        const std::vector<std::int64_t> global = number_regions(counts, all_links);
        std::size_t at = 0;
        for (const std::vector<std::int64_t>& c : counts)
        {
            std::vector<std::int64_t> part(global.begin() + static_cast<std::ptrdiff_t>(at),
                                           global.begin() + static_cast<std::ptrdiff_t>(at + c[0]));
            part.push_back(global.back());
            per_rank.push_back(std::move(part));
            at += static_cast<std::size_t>(c[0]);
        }
    }
    const std::vector<std::int64_t> numbers = comm.scatter_values(per_rank);
    std::vector<std::vector<Index>> out(static_cast<std::size_t>(numbers.back()));
    for (std::size_t r = 0; r < local.size(); ++r)
    {
        std::vector<Index>& cells = out[static_cast<std::size_t>(numbers[r])];
        cells.insert(cells.end(), local[r].begin(), local[r].end());
    }
    for (std::vector<Index>& cells : out)
        std::sort(cells.begin(), cells.end());
    return out;
}

} // namespace meshmorph
