// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Write polyMesh files as OpenFOAM does (docs/polymesh-format.md §9): `points` alone
//! (a morph), or a whole polyMesh. Every file is written atomically (temporary + rename).
//!
//! A file read and written unchanged is reproduced exactly: same format, compression, class,
//! arch; ASCII numbers at 17 significant digits so values survive the round trip; binary
//! blocks raw little-endian.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/io/read_poly_mesh.h"

namespace meshmorph::io
{

//! Options shared by the writers. Unset optionals keep the form of the file read.
struct PolyMeshWriteOptions
{
    std::optional<FoamFormat> format; //!< override ascii/binary for every file
    std::optional<bool> compress;     //!< override gzip compression for every file
    int precision = 17;               //!< significant digits of ASCII scalars
    //! Binary label size (4 or 8); 0 keeps the size read (sizeof(Index) for new files).
    int label_bytes = 0;
};

//! \brief The `location` header value of a polyMesh file of `instance` and `region`:
//! "constant/polyMesh", "1/polyMesh", "constant/fluid/polyMesh".
std::string poly_mesh_location(const std::string& instance, const std::string& region = "");

//! \brief Write `points` (nPoints x 3) to `<case>/<instance>[/<region>]/polyMesh/points`,
//! creating directories, in the form of `like` (the points file read: format, compression,
//! header `version`/`class`; `location` set to the instance written, `object points`; arch
//! with scalar=64 in binary). Never leaves both `points` and `points.gz`. Warns when the
//! directory holds a `tetBasePtIs`, which depends on the geometry and goes stale.
//! Returns the path written.
//! \throw IoError naming the path on failure (the old file is then unchanged).
std::filesystem::path write_points(const Points& points, const FoamFileInfo& like,
                                   const std::filesystem::path& case_dir,
                                   const std::string& instance, const std::string& region = "",
                                   const PolyMeshWriteOptions& options = {});

//! \brief Write `points` to the file `path` (`.../polyMesh/points`; `.gz` is appended when
//! compressing) with the header of `like` and `location` as given.
std::filesystem::path write_points_file(const Points& points, const FoamFileInfo& like,
                                        const std::filesystem::path& path,
                                        const std::string& location,
                                        const PolyMeshWriteOptions& options = {});

//! \brief FoamFileInfo for a file meshmorph creates from scratch (no file read): the
//! class OpenFOAM uses for `object` in that format (faces: faceList in ASCII,
//! faceCompactList in binary), native label size, scalar=64.
FoamFileInfo default_file_info(const std::string& object, FoamFormat format, bool compress = false);

//! \brief FoamPolyMesh metadata for writing a generated mesh in one format.
FoamPolyMesh default_poly_mesh_files(FoamFormat format, bool compress = false);

//! \brief Write every polyMesh file of `mesh` (points, faces, owner, neighbour, boundary,
//! and the zone files when `mesh` has zones or `like` had them) to
//! `<case>/<instance>[/<region>]/polyMesh`, each in the form recorded in `like` (see
//! default_poly_mesh_files for a new mesh). owner/neighbour carry OpenFOAM's
//! `note "nPoints:..  nCells:..  nFaces:..  nInternalFaces:.."`. Faces are a `faceList` in
//! ASCII and a `faceCompactList` in binary unless the format is unchanged from `like`.
//! Returns the polyMesh directory.
//! \throw IoError naming the path on failure.
std::filesystem::path write_poly_mesh(const PolyMesh& mesh, const FoamPolyMesh& like,
                                      const std::filesystem::path& case_dir,
                                      const std::string& instance, const std::string& region = "",
                                      const PolyMeshWriteOptions& options = {});

//! \brief Write every polyMesh file into the directory `poly_mesh_dir` with header
//! `location` as given (see write_poly_mesh).
std::filesystem::path write_poly_mesh_dir(const PolyMesh& mesh, const FoamPolyMesh& like,
                                          const std::filesystem::path& poly_mesh_dir,
                                          const std::string& location,
                                          const PolyMeshWriteOptions& options = {});

} // namespace meshmorph::io
