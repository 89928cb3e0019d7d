// SPDX-License-Identifier: GPL-3.0-or-later
//! \file What a morph writes, and how it keeps the case safe while it does: the points
//! (atomically; with -overwrite the original kept first as points.orig), the warnings
//! about results replaced or left behind, and the VTK file of the result.
#pragma once

#include <filesystem>
#include <string>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/morph/morph_result.h"

namespace meshmorph::morph
{

//! The start of the header `note` of every points file morphMesh writes: a morph's result
//! is recognisable as such (OpenFOAM reads and ignores the note).
constexpr const char* morph_note_prefix = "morphed by morphMesh";

//! The note of a points file morphed from the points of `instance`.
std::string morph_result_note(const std::string& instance);

//! Whether a header is that of points morphMesh wrote.
bool is_morph_result(const io::FoamHeader& header);

//! The morphed points, and with -overwrite the original kept first; a failure removes what
//! this run created, so a failed write leaves the case as it was.
std::filesystem::path write_morphed_points(const MorphOptions& options, const Points& points,
                                           const io::FoamPolyMesh& foam,
                                           const std::filesystem::path& mesh_case,
                                           const std::string& instance);

//! Without -overwrite the morph replaces points already at the time it writes (an earlier
//! morph's, or another tool's such as reconstructPar's): say so.
void warn_if_replacing(const std::filesystem::path& case_dir, const std::string& instance,
                       const std::string& region);

//! A decomposed case keeps its own copy of the mesh in every processor directory: a serial
//! morph changes only the undecomposed mesh, and a parallel run would use the old one.
void warn_if_decomposed(const std::filesystem::path& case_dir);

//! -vtk: the morphed mesh with the displacement and the quality fields.
void write_vtk(const std::filesystem::path& case_dir, const MorphOptions& options,
               const PolyMesh& moved, MorphResult& result);

} // namespace meshmorph::morph
