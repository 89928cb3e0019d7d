// SPDX-License-Identifier: GPL-3.0-or-later
// Derived addressing of a PolyMesh.
#include "meshmorph/core/poly_mesh.h"

#include <algorithm>

namespace meshmorph
{

void PolyMesh::finalize()
{
    Index max_cell = -1;
    for (Index c : owner)
        max_cell = std::max(max_cell, c);
    for (Index c : neighbour)
        max_cell = std::max(max_cell, c);
    n_cells = max_cell + 1;
}

Index PolyMesh::which_patch(Index f) const
{
    if (f < n_internal_faces())
        return -1;
    // Patches are contiguous and ordered; binary search on start_face.
    auto it = std::upper_bound(patches.begin(), patches.end(), f,
                               [](Index face, const Patch& p) { return face < p.start_face; });
    while (it != patches.begin())
    {
        --it;
        if (f >= it->start_face && f < it->start_face + it->n_faces)
            return static_cast<Index>(it - patches.begin());
        if (it->n_faces > 0)
            break;
    }
    return -1;
}

Index PolyMesh::find_patch(const std::string& name) const
{
    for (std::size_t i = 0; i < patches.size(); ++i)
        if (patches[i].name == name)
            return static_cast<Index>(i);
    return -1;
}

CompactList cell_faces(const PolyMesh& mesh)
{
    const Index n_cells = mesh.n_cells;
    CompactList result;
    result.offsets.assign(static_cast<std::size_t>(n_cells) + 1, 0);
    for (Index c : mesh.owner)
        ++result.offsets[c + 1];
    for (Index c : mesh.neighbour)
        ++result.offsets[c + 1];
    for (Index c = 0; c < n_cells; ++c)
        result.offsets[c + 1] += result.offsets[c];
    result.values.resize(result.offsets[n_cells]);
    std::vector<Index> fill(result.offsets.begin(), result.offsets.end() - 1);
    for (Index f = 0; f < mesh.n_faces(); ++f)
        result.values[fill[mesh.owner[f]]++] = f;
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
        result.values[fill[mesh.neighbour[f]]++] = f;
    return result;
}

namespace
{

//! The distinct points of cells [begin, end), in order of first appearance.
CompactList cell_points_of(const PolyMesh& mesh, const CompactList& cf, Index begin, Index end)
{
    CompactList result;
    result.offsets.reserve(std::size_t(end - begin) + 1);
    result.values.reserve(std::size_t(cf.offsets[end] - cf.offsets[begin]) * 2);
    std::vector<Index> cell_points_buf;
    for (Index c = begin; c < end; ++c)
    {
        cell_points_buf.clear();
        for (Index f : cf[c])
            for (Index p : mesh.faces[f])
                if (std::find(cell_points_buf.begin(), cell_points_buf.end(), p) ==
                    cell_points_buf.end())
                    cell_points_buf.push_back(p);
        result.push_back(std::span<const Index>(cell_points_buf));
    }
    return result;
}

} // namespace

CompactList cell_points(const PolyMesh& mesh, const CompactList& cf)
{
    // In a fixed number of pieces (the same result on any number of threads), concatenated.
    constexpr Index pieces = 16;
    const Index n = cf.size();
    std::vector<CompactList> parts(static_cast<std::size_t>(pieces));
#pragma omp parallel for schedule(dynamic, 1) if (n > 65536)
    for (Index k = 0; k < pieces; ++k)
        parts[std::size_t(k)] = cell_points_of(mesh, cf, n * k / pieces, n * (k + 1) / pieces);
    CompactList result;
    result.offsets.reserve(std::size_t(n) + 1);
    std::size_t total = 0;
    for (const CompactList& part : parts)
        total += part.values.size();
    result.values.reserve(total);
    for (const CompactList& part : parts)
    {
        const Index shift = Index(result.values.size());
        for (std::size_t i = 1; i < part.offsets.size(); ++i)
            result.offsets.push_back(part.offsets[i] + shift);
        result.values.insert(result.values.end(), part.values.begin(), part.values.end());
    }
    return result;
}

std::vector<Index> patch_points(const PolyMesh& mesh, const Patch& patch)
{
    std::vector<Index> result;
    std::vector<char> seen(static_cast<std::size_t>(mesh.n_points()), 0);
    for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
        for (Index p : mesh.faces[f])
            if (!seen[p])
            {
                seen[p] = 1;
                result.push_back(p);
            }
    return result;
}

std::vector<char> boundary_point_mask(const PolyMesh& mesh)
{
    std::vector<char> mask(static_cast<std::size_t>(mesh.n_points()), 0);
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
        for (Index p : mesh.faces[f])
            mask[p] = 1;
    return mask;
}

const std::string* find_entry(const Patch& patch, std::string_view key)
{
    for (const auto& [k, v] : patch.entries)
        if (k == key)
            return &v;
    return nullptr;
}

} // namespace meshmorph
