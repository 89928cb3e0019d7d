// SPDX-License-Identifier: GPL-3.0-or-later
//! \file checkMesh -meshQuality: snappyHexMesh's meshQualityDict criteria (OpenFOAM
//! motionSmoother::checkMesh with polyMeshGeometry's checks), docs/checkmesh-spec.md §5.
#pragma once

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/coupled_patches.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/quality/check_result.h"
#include "meshmorph/quality/check_settings.h"

namespace meshmorph
{

//! \brief Every enabled criterion, in OpenFOAM's order, flags faces; each counts the faces
//! it adds to the cumulative set of faces in error (OpenFOAM's "faces in error" lines).
//! Fails "meshQuality" when any face is in error. Statistics meshQualityFailures
//! (criterion key -> faces newly flagged), meshQualityFaces; set meshQualityFaces.
//! Coupled faces (cyclic, processor) are measured against the cell across them where
//! polyMeshGeometry does: non-orthogonality, skewness (with the internal limit), weights,
//! volume ratio, twist and the tets' shared base point.
//! \param skewness face_skewness(mesh, geometry, coupled) (maxInternalSkewness uses checkMesh's).
//! \param coupled coupled_faces(mesh, geometry, ...).
CheckResult check_mesh_quality(const PolyMesh& mesh, const CompactList& cell_faces,
                               const MeshGeometry& geometry, const MeshQualitySettings& settings,
                               const Eigen::VectorXd& skewness, const CoupledFaces& coupled);

} // namespace meshmorph
