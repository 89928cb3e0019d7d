// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Write a pointVectorField that OpenFOAM reads back (e.g. `dJdXs`, a sensitivity on
//! the mesh points): ASCII, values at 17 significant digits, written atomically.
#pragma once

#include <filesystem>
#include <string>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph::io
{

//! \brief Write `values` (nPoints x 3) as the pointVectorField `path` (its file name is the
//! object): the internalField, and per patch its points' values as a `calculated` patch
//! field, or the patch's own type for the constraint types OpenFOAM requires to match
//! (empty, wedge, symmetry, symmetryPlane, cyclic, cyclicAMI, cyclicSlip, processor,
//! processorCyclic). `location` goes to the header, `note` (if any) to a comment above it.
//! \return the path written. \throw InvalidInput for a wrong row count; IoError naming the
//! path (the old file is then unchanged).
std::filesystem::path write_point_vector_field(const std::filesystem::path& path,
                                               const PolyMesh& mesh, const Points& values,
                                               const std::string& location,
                                               const std::string& note = "");

} // namespace meshmorph::io
