// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A decomposed case (decomposePar's processor<N> directories) as both applications
//! read it with -parallel: this rank's directory, the list of them, and the point
//! addressing back to the undecomposed mesh.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::io
{

//! \brief `<case>/processor<rank>`: this rank's part. Every rank checks its own; the master
//! checks that there is one per rank (OpenFOAM's rule) and refuses the collated layout.
//! \param tool the application, for the messages. A collective.
std::filesystem::path processor_case(const std::filesystem::path& case_dir,
                                     const parallel::Communicator& comm, const std::string& tool);

//! \brief processor0, processor1, ... (uncollated) and processors<N> (collated) in the case.
std::vector<std::string> processor_directories(const std::filesystem::path& case_dir);

//! \brief This rank's point labels in the undecomposed mesh (decomposePar's
//! pointProcAddressing beside the faces). \throw InvalidInput naming the file if it does not
//! fit the mesh.
std::vector<Index> read_point_addressing(const FoamPolyMesh& foam);

//! \brief The undecomposed mesh's number of points: the largest label over every rank + 1.
Index global_point_count(const std::vector<Index>& point_addressing,
                         const parallel::Communicator& comm);

} // namespace meshmorph::io
