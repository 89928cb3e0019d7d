// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Face flatness: the face's area over the summed areas of the triangles fanned from
//! its centre (OpenFOAM primitiveMeshTools::faceFlatness; 1 for a flat face, towards 0 for a
//! butterfly).
#pragma once

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

//! \brief Per face, the summed |area| of the triangles (p[i], p[i+1], face centre).
//! OpenMP over faces. \return nFaces values (0 for a face without points).
Eigen::VectorXd face_fan_areas(const PolyMesh& mesh, const MeshGeometry& geometry);

//! \brief checkMesh's flatness |Af| / (fan area + ROOTVSMALL) per face; 1 for triangles and
//! for faces with |Af| <= ROOTVSMALL. OpenMP over faces.
//! \param face_area_magnitudes face_area_magnitudes(geometry). \return nFaces values.
Eigen::VectorXd face_flatness(const PolyMesh& mesh, const MeshGeometry& geometry,
                              const Eigen::VectorXd& face_area_magnitudes);

} // namespace meshmorph
