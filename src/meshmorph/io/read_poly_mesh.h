// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Read an OpenFOAM polyMesh (points, faces, owner, neighbour, boundary, zones) from a
//! case, validated, with the metadata needed to write it back in the same form.
//!
//! Usage:
//! \code
//!   io::FoamPolyMesh m = io::read_poly_mesh(case_dir, {io::TimeSelection::latest_time()});
//!   // ... move m.mesh.points ...
//!   io::write_points(m.mesh.points, m.points, case_dir, "1");   // write_poly_mesh.h
//! \endcode
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/io/case_instance.h"
#include "meshmorph/io/foam_header.h"

namespace meshmorph::io
{

//! How one polyMesh file was stored, so that it can be written back in the same form.
struct FoamFileInfo
{
    std::filesystem::path path; //!< the file read (`X` or `X.gz`)
    FoamHeader header;          //!< its FoamFile header (format, class, arch, location, ...)
    bool is_compressed = false; //!< read from gzip data
    std::size_t bytes = 0;      //!< size of the (decompressed) contents in bytes
};

//! A PolyMesh plus where and how its files are stored.
struct FoamPolyMesh
{
    PolyMesh mesh;
    std::filesystem::path case_dir;   //!< empty when read with read_poly_mesh_dir
    std::string region;               //!< "" for the default region
    std::string time;                 //!< the selected time ("constant" or a time name)
    std::string points_instance;      //!< instance holding `points` ("constant" or a time)
    std::string faces_instance;       //!< instance holding faces/owner/neighbour/boundary
    std::filesystem::path points_dir; //!< polyMesh directory `points` was read from
    std::filesystem::path faces_dir;  //!< polyMesh directory of the topology files
    FoamFileInfo points;
    FoamFileInfo faces;
    FoamFileInfo owner;
    FoamFileInfo neighbour;
    FoamFileInfo boundary;
    std::optional<FoamFileInfo> point_zones; //!< set when the file exists
    std::optional<FoamFileInfo> face_zones;
    std::optional<FoamFileInfo> cell_zones;
    //! Whether the topology directory has `tetBasePtIs`, which goes stale when points move.
    bool has_tet_base_pt_is = false;

    //! Total (decompressed) bytes of all files read.
    std::size_t total_bytes() const;
};

//! Options of read_poly_mesh.
struct PolyMeshReadOptions
{
    TimeSelection time;     //!< which time to read (default: the earliest, or constant)
    std::string region;     //!< `-region`; "" for the default region
    bool read_zones = true; //!< read cellZones/faceZones/pointZones when present
    bool parallel = true;   //!< parse large ASCII lists with OpenMP threads
};

//! \brief Read the polyMesh of `case_dir` at the selected time: points from the points
//! instance, topology from the faces instance (docs/polymesh-format.md §1). Files may be
//! plain or `.gz`, ASCII or binary, with 32 or 64-bit labels and scalars.
//!
//! Validated (docs/polymesh-format.md §5-6): header class (a different `object` only warns),
//! every list size against its declaration and the bytes left, owner size == faces size,
//! neighbour size <= faces size (a legacy neighbour padded with -1 is cut at the first -1),
//! faces with >= 3 vertices whose labels are in [0, nPoints), non-negative owner and
//! neighbour, owner < neighbour on internal faces, patches contiguous from nInternalFaces to
//! nFaces, zone labels in range, finite point coordinates.
//! \throw IoError if a required file is missing or unreadable (message names the path).
//! \throw ParseError naming the file and line (ASCII) or byte offset (binary) on malformed
//! content or an invalid mesh. \throw InvalidInput on a bad time selection.
FoamPolyMesh read_poly_mesh(const std::filesystem::path& case_dir,
                            const PolyMeshReadOptions& options = {});

//! \brief Read the files of one polyMesh directory (`.../polyMesh`), all from that directory.
//! case_dir/instances in the result are left empty.
FoamPolyMesh read_poly_mesh_dir(const std::filesystem::path& poly_mesh_dir,
                                const PolyMeshReadOptions& options = {});

//! \brief Read only `points` (plain or .gz) as a vectorField.
//! \param info when not null, receives the file's metadata.
//! \brief A labelList file whose labels are all >= 0, e.g. decomposePar's
//! processor<N>/constant/polyMesh/pointProcAddressing (the undecomposed mesh's label of each
//! processor point). \throw IoError, ParseError naming the file and line.
std::vector<Index> read_label_list_file(const std::filesystem::path& path,
                                        const std::string& object);

//! \throw IoError, ParseError as read_poly_mesh.
Points read_points_file(const std::filesystem::path& path, FoamFileInfo* info = nullptr,
                        bool parallel = true);

} // namespace meshmorph::io
