// SPDX-License-Identifier: GPL-3.0-or-later
// checkMesh's topology checks.
#include "meshmorph/quality/topology_checks.h"

#include <algorithm>
#include <string>

#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/patch_kinds.h"
#include "meshmorph/quality/cell_regions.h"

namespace meshmorph
{

namespace
{

//! The number of repeated vertices of a face, each repetition counted once (as OpenFOAM's
//! hash-set insert).
Index repeated_vertices(std::span<const Index> face, std::vector<Index>& scratch)
{
    Index repeats = 0;
    if (face.size() <= 16)
    {
        for (std::size_t i = 1; i < face.size(); ++i)
            for (std::size_t j = 0; j < i; ++j)
                if (face[i] == face[j])
                {
                    ++repeats;
                    break;
                }
        return repeats;
    }
    scratch.assign(face.begin(), face.end());
    std::sort(scratch.begin(), scratch.end());
    for (std::size_t i = 1; i < scratch.size(); ++i)
        repeats += scratch[i] == scratch[i - 1];
    return repeats;
}

//! Upper-triangular order within one cell: its higher neighbours must be reached through
//! faces in increasing order, each neighbour through one face. Appends offending faces;
//! returns (several faces to one neighbour, order error).
std::pair<bool, bool> cell_face_order(const PolyMesh& mesh, std::span<const Index> faces,
                                      Index cell, std::vector<std::pair<Index, Index>>& nbr,
                                      std::vector<Index>& bad)
{
    nbr.clear(); // (neighbour cell, face)
    for (Index f : faces)
    {
        if (f >= mesh.n_internal_faces())
            continue;
        const Index other = mesh.neighbour[f] == cell ? mesh.owner[f] : mesh.neighbour[f];
        if (cell < other)
            nbr.emplace_back(other, f);
    }
    std::stable_sort(nbr.begin(), nbr.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    bool multiple = false, error = false;
    for (std::size_t i = 1; i < nbr.size(); ++i)
    {
        if (nbr[i].first == nbr[i - 1].first)
        {
            multiple = true;
            bad.push_back(nbr[i - 1].second);
            bad.push_back(nbr[i].second);
        }
        else if (nbr[i].second < nbr[i - 1].second)
        {
            error = true;
            bad.push_back(nbr[i].second);
        }
    }
    return {multiple, error};
}

} // namespace

CheckResult check_boundary_definition(const PolyMesh& mesh)
{
    bool ok = true;
    Index next = mesh.n_internal_faces();
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
    {
        const Patch& p = mesh.patches[i];
        if (p.start_face != next)
            ok = false;
        next = p.start_face + p.n_faces;
        for (std::size_t j = 0; j < i; ++j)
            if (mesh.patches[j].name == p.name)
                ok = false;
    }
    if (next != mesh.n_faces())
        ok = false;
    CheckResult r(CheckId::boundary_definition);
    r.add("boundaryDefinitionOK", Index{ok}, false);
    return r;
}

CheckResult check_empty_patches(const PolyMesh& mesh)
{
    Index n_empty = 0;
    for (const Patch& p : mesh.patches)
        if (p.type == "empty")
            n_empty += p.n_faces;
    CheckResult r(CheckId::empty_patches);
    r.add("emptyFacesDivisible", Index{!(mesh.n_cells > 0 && n_empty % mesh.n_cells != 0)}, false);
    return r;
}

CheckResult check_cell_addressing(const PolyMesh& mesh, const CompactList& cell_faces)
{
    std::vector<Index> illegal;
    for (Index cell = 0; cell < mesh.n_cells; ++cell)
    {
        const std::span<const Index> cf = cell_faces[cell];
        bool bad = cf.size() <= 3;
        for (Index f : cf)
            bad = bad || f < 0 || f >= mesh.n_faces();
        if (bad)
            illegal.push_back(cell);
    }
    CheckResult r(CheckId::cell_addressing);
    r.add("illegalCells", size_of(illegal), false);
    if (!illegal.empty())
        r.failure = "illegalCells";
    r.add_set("illegalCells", MeshSet::Kind::cell, std::move(illegal), "illegal cells");
    return r;
}

CheckResult check_point_usage(const PolyMesh& mesh)
{
    std::vector<char> used(static_cast<std::size_t>(mesh.n_points()), 0);
    for (Index p : mesh.faces.values)
        used[p] = 1;
    std::vector<Index> unused;
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (!used[p])
            unused.push_back(p);
    CheckResult r(CheckId::point_usage);
    // Every face has an owner cell, so points unused by faces are exactly the points unused
    // by cells.
    r.add("unusedPoints", size_of(unused), false);
    if (!unused.empty())
        r.failure = "unusedPoints";
    r.add_set("unusedPoints", MeshSet::Kind::point, std::move(unused), "unused points");
    return r;
}

CheckResult check_upper_triangular(const PolyMesh& mesh, const CompactList& cell_faces)
{
    bool error = false;
    std::vector<Index> bad;
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
        if (mesh.owner[f] >= mesh.neighbour[f])
        {
            error = true;
            bad.push_back(f);
        }
    Index n_multiple = 0;
    std::vector<std::pair<Index, Index>> nbr;
    for (Index cell = 0; cell < mesh.n_cells; ++cell)
    {
        const auto [multiple, order_error] =
            cell_face_order(mesh, cell_faces[cell], cell, nbr, bad);
        n_multiple += multiple;
        error = error || order_error;
    }
    CheckResult r(CheckId::upper_triangular);
    r.add("cellsWithMultipleFaces", n_multiple, false);
    if (error)
        r.failure = "upperTriangular";
    r.add_set("upperTriangularFace", MeshSet::Kind::face, std::move(bad), "unordered faces");
    return r;
}

CheckResult check_face_vertices(const PolyMesh& mesh)
{
    Index n_error = 0;
    std::vector<Index> bad;
    std::vector<Index> scratch;
    for (Index f = 0; f < mesh.n_faces(); ++f)
        if (const Index repeats = repeated_vertices(mesh.faces[f], scratch); repeats > 0)
        {
            n_error += repeats;
            bad.push_back(f);
        }
    CheckResult r(CheckId::face_vertices);
    r.add("faceVertexErrors", n_error, false);
    if (n_error > 0)
        r.failure = "faceVertices";
    r.add_set("outOfRangeFaces", MeshSet::Kind::face, std::move(bad),
              "faces with out-of-range or duplicate vertices");
    return r;
}

CheckResult check_cells_zip_up(const CellEdgeUsage& usage)
{
    Index n_open = 0;
    std::vector<Index> zip;
    for (std::size_t cell = 0; cell < usage.open.size(); ++cell)
    {
        n_open += usage.open[cell];
        if (usage.open[cell] || usage.over_used[cell])
            zip.push_back(static_cast<Index>(cell));
    }
    CheckResult r(CheckId::cells_zip_up);
    r.add("openCells", n_open, false);
    if (n_open > 0)
    {
        r.failure = "cellsZipUp";
        r.add_set("zipUpCells", MeshSet::Kind::cell, std::move(zip), "cells with over used edges");
    }
    return r;
}

CheckResult check_face_faces(const FaceFaceConnectivity& c)
{
    Index baffles = 0, duplicates = 0, order_errors = 0;
    for (std::size_t f = 0; f < c.baffles.size(); ++f)
    {
        baffles += c.baffles[f];
        duplicates += c.duplicates[f];
        order_errors += c.order_errors[f];
    }
    CheckResult r(CheckId::face_faces);
    r.add("baffleFaces", baffles, false);
    r.add("duplicateFaces", duplicates, false);
    r.add("nonConsecutiveFaces", order_errors, false);
    r.add_set("edgeFaces", MeshSet::Kind::face, flagged(c.in_pair),
              "faces with non-standard edge connectivity");
    return r;
}

CheckResult check_internal_face_cells(const PolyMesh& mesh, const ProcessorFaces* processors)
{
    std::vector<Index> n_internal(static_cast<std::size_t>(mesh.n_cells), 0);
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
    {
        ++n_internal[mesh.owner[f]];
        ++n_internal[mesh.neighbour[f]];
    }
    // A coupled face joins two cells as an internal one does (checkTopology.C).
    for (const Patch& p : mesh.patches)
        if (is_coupled_patch(p))
            for (Index f = p.start_face; f < p.start_face + p.n_faces; ++f)
                ++n_internal[mesh.owner[f]];
    if (processors)
        for (std::size_t b = 0; b < processors->on_processor_patch.size(); ++b)
            if (processors->on_processor_patch[b])
                ++n_internal[mesh.owner[mesh.n_internal_faces() + static_cast<Index>(b)]];
    std::vector<Index> one, two;
    for (Index cell = 0; cell < mesh.n_cells; ++cell)
    {
        if (n_internal[cell] <= 1)
            one.push_back(cell);
        else if (n_internal[cell] == 2)
            two.push_back(cell);
    }
    CheckResult r(CheckId::internal_face_cells);
    r.add_set("oneInternalFaceCells", MeshSet::Kind::cell, std::move(one),
              "cells with zero or one non-boundary face");
    r.add_set("twoInternalFacesCells", MeshSet::Kind::cell, std::move(two),
              "cells with two non-boundary faces");
    return r;
}

CheckResult check_regions(const PolyMesh& mesh, const std::vector<std::vector<Index>>& regions,
                          bool all_topology)
{
    CheckResult r(CheckId::regions);
    r.add("regions", size_of(regions), false);
    if (regions.size() <= 1)
        return r;
    for (std::size_t i = 0; i < regions.size(); ++i)
        r.add_set("region" + std::to_string(i), MeshSet::Kind::cell, regions[i], "");
    if (!all_topology)
        return r;
    // checkTopology.C: walk the boundary faces' points; a point reached from two regions
    // connects them (neither is "fully disconnected") and goes into multiRegionPoints.
    constexpr Index unassigned = -1, several = -2;
    const std::vector<Index> cell_region = region_of_cells(regions, mesh.n_cells);
    std::vector<Index> point_region(static_cast<std::size_t>(mesh.n_points()), unassigned);
    std::vector<char> disconnected(regions.size(), 1);
    std::vector<Index> multi_region_points;
    for (Index f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f)
    {
        const Index region = cell_region[static_cast<std::size_t>(mesh.owner[f])];
        for (Index p : mesh.faces[f])
        {
            Index& seen = point_region[static_cast<std::size_t>(p)];
            if (seen == unassigned)
                seen = region;
            else if (seen == several)
                disconnected[static_cast<std::size_t>(region)] = 0;
            else if (seen != region)
            {
                disconnected[static_cast<std::size_t>(region)] = 0;
                disconnected[static_cast<std::size_t>(seen)] = 0;
                seen = several;
                multi_region_points.push_back(p);
            }
        }
    }
    Statistic::Counts flags;
    for (std::size_t i = 0; i < regions.size(); ++i)
        flags.emplace_back("region" + std::to_string(i), Index{disconnected[i]});
    r.add("regionDisconnected", std::move(flags), false);
    r.add_set("multiRegionPoints", MeshSet::Kind::point, std::move(multi_region_points),
              "points that are in multiple regions");
    return r;
}

} // namespace meshmorph
