// SPDX-License-Identifier: GPL-3.0-or-later
// Cell edge use counts in a small open-addressing hash table per thread (faster than sorting
// each cell's edges); only the used slots are reset after each cell.
#include "meshmorph/quality/cell_edge_usage.h"

#include <algorithm>
#include <cstdint>

#include "meshmorph/mesh/foam_vector.h"
#include "meshmorph/quality/mesh_edges.h"

namespace meshmorph
{

namespace
{

class EdgeUseTable
{
public:
    //! Count the edges of one cell; then open() / over_used() tell the result.
    void count(const PolyMesh& mesh, std::span<const Index> faces)
    {
        std::size_t n_edges = 0;
        for (Index f : faces)
            n_edges += static_cast<std::size_t>(mesh.faces.item_size(f));
        bits_ = 4;
        while ((std::size_t{1} << bits_) < 2 * n_edges)
            ++bits_;
        const std::size_t capacity = std::size_t{1} << bits_;
        if (keys_.size() < capacity)
        {
            keys_.resize(capacity, empty);
            uses_.resize(capacity, 0);
        }
        used_slots_.clear();
        for (Index f : faces)
        {
            const std::span<const Index> face = mesh.faces[f];
            for (std::size_t i = 0; i < face.size(); ++i)
                ++uses_[slot(packed_edge(face[i], face[(i + 1) % face.size()]))];
        }
    }

    //! Whether an edge is used once (open) / more than twice; resets the table.
    std::pair<bool, bool> open_and_over_used()
    {
        bool open = false, over_used = false;
        for (const std::uint32_t h : used_slots_)
        {
            if (uses_[h] == 1)
                open = true;
            else if (uses_[h] != 2)
                over_used = true;
            keys_[h] = empty;
            uses_[h] = 0;
        }
        return {open, over_used};
    }

private:
    static constexpr std::uint64_t empty = ~std::uint64_t{0}; // no valid packed edge

    std::size_t slot(std::uint64_t e)
    {
        const std::size_t mask = (std::size_t{1} << bits_) - 1;
        std::size_t h = (e * 0x9E3779B97F4A7C15ull) >> (64 - bits_);
        while (keys_[h] != empty && keys_[h] != e)
            h = (h + 1) & mask;
        if (keys_[h] == empty)
        {
            keys_[h] = e;
            used_slots_.push_back(static_cast<std::uint32_t>(h));
        }
        return h;
    }

    int bits_ = 4;
    std::vector<std::uint64_t> keys_;
    std::vector<std::uint32_t> uses_;
    std::vector<std::uint32_t> used_slots_;
};

} // namespace

CellEdgeUsage cell_edge_usage(const PolyMesh& mesh, const CompactList& cell_faces)
{
    const Index n_cells = mesh.n_cells;
    CellEdgeUsage usage{std::vector<char>(static_cast<std::size_t>(n_cells), 0),
                        std::vector<char>(static_cast<std::size_t>(n_cells), 0)};
#pragma omp parallel if (mesh.n_faces() > detail::parallel_threshold)
    {
        EdgeUseTable table;
#pragma omp for schedule(dynamic, 2048)
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            table.count(mesh, cell_faces[cell]);
            const auto [open, over_used] = table.open_and_over_used();
            usage.open[cell] = open;
            usage.over_used[cell] = over_used;
        }
    }
    return usage;
}

} // namespace meshmorph
