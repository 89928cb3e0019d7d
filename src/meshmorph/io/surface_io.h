// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Reading triangle surfaces (STL ascii/binary, Wavefront OBJ, plain or gzip) through
//! the whole-file reader of foam_file.h.
#pragma once

#include <filesystem>

#include "meshmorph/core/triangle_surface.h"

namespace meshmorph::io
{

//! \brief Read an STL file, ASCII or binary (told apart by the binary size rule
//! 84 + 50 m bytes, since binary headers may also start with "solid"); all solids of an ASCII
//! file are concatenated. Vertices with identical coordinates are merged, so the result is
//! indexed (STL itself is a triangle soup). Facet normals are ignored: the vertex order gives
//! the orientation. Gzip data is decompressed, and, as OpenFOAM does, `path.gz` is read when
//! `path` does not exist (foam_file.h's read_foam_file).
//! \throw IoError if the file cannot be read.
//! \throw ParseError naming the file and line (ASCII) or byte offset (binary) on malformed
//!        content: unexpected keyword, bad or non-finite number, truncated data, no triangles.
TriangleSurface read_stl(const std::filesystem::path& path);

//! \brief Read a Wavefront OBJ file: `v x y z [w]` and `f` lines (`i`, `i/t`, `i//n`, `i/t/n`,
//! negative = relative indices); polygons are fan-triangulated from their first vertex; other
//! statements (vn, vt, g, o, s, usemtl, mtllib, l, ...) are ignored. Compressed files as for
//! read_stl.
//! \throw IoError if unreadable. \throw ParseError (file:line) on a malformed number, an index
//!        out of range, a face with fewer than 3 vertices, or no faces at all.
TriangleSurface read_obj(const std::filesystem::path& path);

//! \brief read_stl or read_obj by extension (`.stl`, `.obj`, case-insensitive, optionally
//! followed by `.gz`). \throw InvalidInput for another extension (message lists the supported
//! ones), else as the readers.
TriangleSurface read_surface(const std::filesystem::path& path);

} // namespace meshmorph::io
