// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Face pyramid volumes (OpenFOAM primitiveMeshTools::facePyramidVolume): the pyramid
//! of a face with its apex at the owner (neighbour) cell centre, positive when the face
//! points away from the apex as it should.
#pragma once

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/types.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

struct FacePyramidVolumes
{
    Eigen::VectorXd owner;     //!< nFaces: -(1/3) Af . (Cc(owner) - Cf)
    Eigen::VectorXd neighbour; //!< nInternalFaces: (1/3) Af . (Cc(neighbour) - Cf)
};

//! Whether a pyramid of this volume is wrongly oriented, as checkMesh decides: below -SMALL,
//! or not a number (non-finite points).
inline bool wrongly_oriented(double pyramid_volume)
{
    return !(pyramid_volume >= -constants::small);
}

//! \brief Both pyramid volumes of every face. OpenMP over faces.
FacePyramidVolumes face_pyramid_volumes(const PolyMesh& mesh, const MeshGeometry& geometry);

} // namespace meshmorph
