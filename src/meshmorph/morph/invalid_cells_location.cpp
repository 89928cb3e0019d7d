// SPDX-License-Identifier: GPL-3.0-or-later
// The patches a morph's invalid cells touch.
#include "meshmorph/morph/invalid_cells_location.h"

#include <algorithm>
#include <cstdint>

#include "meshmorph/mesh/patch_kinds.h"
#include "meshmorph/quality/face_pyramids.h"

namespace meshmorph::morph
{

namespace
{

//! The cells a morph is refused for: a volume below OpenFOAM's VSMALL, or a face pyramid
//! of their own that is wrongly oriented (wrongly_oriented()). Each cell
//! is judged by its own pyramids only, so a rank of a -parallel run judges its cells as a
//! serial run does (a processor face's other side is the other rank's cell).
std::vector<Index> invalid_cells(const PolyMesh& mesh, const MeshGeometry& g)
{
    const FacePyramidVolumes v = face_pyramid_volumes(mesh, g);
    std::vector<char> invalid(std::size_t(mesh.n_cells), 0);
    for (Index c = 0; c < mesh.n_cells; ++c)
        invalid[std::size_t(c)] = !(g.cell_volumes[c] >= constants::vsmall);
    for (Index f = 0; f < mesh.n_faces(); ++f)
    {
        if (wrongly_oriented(v.owner[f]))
            invalid[std::size_t(mesh.owner[f])] = 1;
        if (f < mesh.n_internal_faces() && wrongly_oriented(v.neighbour[f]))
            invalid[std::size_t(mesh.neighbour[f])] = 1;
    }
    std::vector<Index> cells;
    for (Index c = 0; c < mesh.n_cells; ++c)
        if (invalid[std::size_t(c)])
            cells.push_back(c);
    return cells;
}

//! The points of `cells`, each once and sorted (`points`), and per cell its points as
//! positions in that list.
struct CellPoints
{
    std::vector<Index> points;
    CompactList slots;
};

CellPoints points_of_cells(const PolyMesh& mesh, const CompactList& cell_faces,
                           const std::vector<Index>& cells)
{
    CellPoints out;
    for (Index c : cells)
        for (Index f : cell_faces[c])
            for (Index p : mesh.faces[f])
                out.points.push_back(p);
    std::sort(out.points.begin(), out.points.end());
    out.points.erase(std::unique(out.points.begin(), out.points.end()), out.points.end());
    for (Index c : cells)
    {
        std::vector<Index> slots;
        for (Index f : cell_faces[c])
            for (Index p : mesh.faces[f])
                slots.push_back(Index(std::lower_bound(out.points.begin(), out.points.end(), p) -
                                      out.points.begin()));
        out.slots.push_back(slots);
    }
    return out;
}

//! Per slot of `cp.points`, 1 when the point lies on `patch`.
std::vector<char> on_patch(const PolyMesh& mesh, const Patch& patch, const CellPoints& cp)
{
    std::vector<char> on(cp.points.size(), 0);
    for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
        for (Index p : mesh.faces[f])
        {
            const auto at = std::lower_bound(cp.points.begin(), cp.points.end(), p);
            if (at != cp.points.end() && *at == p)
                on[std::size_t(at - cp.points.begin())] = 1;
        }
    return on;
}

} // namespace

std::vector<PatchCells> invalid_cells_by_patch(const PolyMesh& mesh, const CompactList& cell_faces,
                                               const MeshGeometry& geometry,
                                               const parallel::Communicator& comm)
{
    const std::vector<Index> cells = invalid_cells(mesh, geometry);
    const CellPoints cp = points_of_cells(mesh, cell_faces, cells);
    std::vector<PatchCells> counts;
    for (const Patch& patch : mesh.patches)
    {
        if (is_processor_patch(patch))
            continue;
        const std::vector<char> on = on_patch(mesh, patch, cp);
        std::int64_t touching = 0;
        for (Index k = 0; k < cp.slots.size(); ++k)
        {
            const auto slots = cp.slots[k];
            touching += std::any_of(slots.begin(), slots.end(),
                                    [&on](Index s) { return on[std::size_t(s)] != 0; })
                            ? 1
                            : 0;
        }
        touching = comm.sum(touching);
        if (touching > 0)
            counts.push_back({patch.name, Index(touching)});
    }
    std::stable_sort(counts.begin(), counts.end(),
                     [](const PatchCells& a, const PatchCells& b) { return a.cells > b.cells; });
    return counts;
}

std::string describe(const std::vector<PatchCells>& counts, std::size_t at_most)
{
    std::string text;
    for (std::size_t k = 0; k < counts.size() && k < at_most; ++k)
        text += (k == 0 ? "" : ", ") + counts[k].patch + " (" + std::to_string(counts[k].cells) +
                " cells)";
    if (counts.size() > at_most)
        text += " and " + std::to_string(counts.size() - at_most) + " more patches";
    return text;
}

} // namespace meshmorph::morph
