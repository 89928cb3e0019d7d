// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The in-memory OpenFOAM polyMesh: points, faces, owner, neighbour, patches, zones.
//!
//! Conventions follow docs/polymesh-format.md §6: faces [0, nInternalFaces) are internal
//! with owner < neighbour, boundary faces follow patch by patch; face normals point from
//! owner to neighbour (out of the domain on the boundary).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph
{

//! Variable-length lists in compressed-row form (OpenFOAM's faceCompactList layout):
//! item i is values[offsets[i] .. offsets[i+1]).
struct CompactList
{
    std::vector<Index> offsets{0}; //!< size() + 1 entries, offsets[0] == 0
    std::vector<Index> values;

    Index size() const { return static_cast<Index>(offsets.size()) - 1; }
    bool empty() const { return size() == 0; }
    std::span<const Index> operator[](Index i) const
    {
        return {values.data() + offsets[i], static_cast<std::size_t>(offsets[i + 1] - offsets[i])};
    }
    Index item_size(Index i) const { return offsets[i + 1] - offsets[i]; }
    //! Append one item.
    void push_back(std::span<const Index> item)
    {
        values.insert(values.end(), item.begin(), item.end());
        offsets.push_back(static_cast<Index>(values.size()));
    }
    void push_back(std::initializer_list<Index> item)
    {
        push_back(std::span<const Index>(item.begin(), item.size()));
    }
    void clear()
    {
        offsets.assign(1, 0);
        values.clear();
    }
    bool operator==(const CompactList&) const = default;
};

//! An ordered keyword -> verbatim value text list, for dictionary entries meshmorph does not
//! interpret but must write back unchanged (e.g. `inGroups 1(wall)`, `neighbourPatch`).
using VerbatimEntries = std::vector<std::pair<std::string, std::string>>;

//! One boundary patch of `constant/polyMesh/boundary`.
struct Patch
{
    std::string name;
    std::string type; //!< patch, wall, empty, wedge, symmetryPlane, cyclic, processor, ...
    Index start_face = 0;
    Index n_faces = 0;
    std::vector<std::string> in_groups; //!< parsed `inGroups` (also kept in `entries`)
    VerbatimEntries entries;            //!< every entry except type/nFaces/startFace, in file order
    bool operator==(const Patch&) const = default;
};

//! One point, face or cell zone.
struct Zone
{
    std::string name;
    std::string type;           //!< pointZone, faceZone, cellZone
    std::vector<Index> labels;  //!< pointLabels / faceLabels / cellLabels
    std::vector<char> flip_map; //!< faceZone only (same size as labels), else empty
    VerbatimEntries entries;    //!< other entries, verbatim
    bool operator==(const Zone&) const = default;
};

//! An OpenFOAM polyMesh in memory. Plain data: readers fill it, algorithms read it.
struct PolyMesh
{
    Points points;                //!< nPoints x 3
    CompactList faces;            //!< nFaces vertex loops
    std::vector<Index> owner;     //!< nFaces
    std::vector<Index> neighbour; //!< nInternalFaces
    std::vector<Patch> patches;
    std::vector<Zone> point_zones;
    std::vector<Zone> face_zones;
    std::vector<Zone> cell_zones;
    Index n_cells = 0; //!< 1 + max(owner, neighbour), set by finalize()

    Index n_points() const { return static_cast<Index>(points.rows()); }
    Index n_faces() const { return faces.size(); }
    Index n_internal_faces() const { return static_cast<Index>(neighbour.size()); }
    bool is_internal_face(Index f) const { return f < n_internal_faces(); }

    //! Recompute n_cells from owner and neighbour.
    void finalize();
    //! Index of the patch holding boundary face f, or -1 for an internal face.
    Index which_patch(Index f) const;
    //! Index of the patch named `name`, or -1.
    Index find_patch(const std::string& name) const;
};

//! Cells' faces (each cell's owned faces in face order, then its neighboured faces).
CompactList cell_faces(const PolyMesh& mesh);
//! Cells' distinct points, in order of first appearance walking cell_faces.
CompactList cell_points(const PolyMesh& mesh, const CompactList& cell_faces);
//! A patch's distinct points in OpenFOAM's patch-local order (first appearance walking
//! the patch faces, docs/polymesh-format.md §6.5).
std::vector<Index> patch_points(const PolyMesh& mesh, const Patch& patch);

//! \brief The verbatim value of the patch's entry `key` (e.g. neighbourPatch, myProcNo), or
//! nullptr when the boundary file does not give it.
const std::string* find_entry(const Patch& patch, std::string_view key);
//! Whether each point is a vertex of some boundary face.
std::vector<char> boundary_point_mask(const PolyMesh& mesh);

} // namespace meshmorph
