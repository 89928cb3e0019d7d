// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Point -> faces addressing (OpenFOAM primitiveMesh::pointFaces).
#pragma once

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! \brief Each point's faces in ascending order, in compressed-row form (a face listing a
//! point twice appears twice). \return nPoints items.
CompactList point_faces(const PolyMesh& mesh);

} // namespace meshmorph
