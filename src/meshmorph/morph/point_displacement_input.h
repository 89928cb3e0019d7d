// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The values of the `type pointDisplacement` entries: `<time>[/<region>]/pointDisplacement`.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::morph
{

//! The pointDisplacement values a type pointDisplacement needs.
struct PointDisplacementInputs
{
    Points internal;
    std::vector<std::optional<Points>> patches;
};

//! <time>[/<region>]/pointDisplacement of the time read (0/ when the mesh came from
//! constant/). Patches of type pointDisplacement take their boundaryField values (fixedValue /
//! calculated), else the internalField at their points; other patches' entries are not used,
//! so their disagreements do not matter here.
PointDisplacementInputs read_point_displacement(const std::filesystem::path& mesh_case,
                                                const io::FoamPolyMesh& foam,
                                                const std::string& region,
                                                const parallel::Communicator& comm);

} // namespace meshmorph::morph
