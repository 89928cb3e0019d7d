// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Cyclic patches as checkMesh couples them (OpenFOAM cyclicPolyPatch, syncTools): face i
//! of a cyclic couples with face i of its neighbourPatch, and positions from the other side
//! reach this one through the patch's transform. The coupled-aware checks (orthogonality,
//! skewness, weights, volume ratio, determinant) measure against the cell across such faces.
//! cyclicAMI is not coupled here: its polyPatch says coupled() false, so checkMesh treats it
//! as a plain boundary.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/mesh/patch_kinds.h"
#include "meshmorph/mesh/processor_faces.h"

namespace meshmorph
{

//! \brief The index of the neighbourPatch of the cyclic patch `patch`.
//! \throws InvalidInput if it names no cyclic patch.
Index cyclic_neighbour_patch(const PolyMesh& mesh, Index patch);

//! One cyclic (or cyclicSlip) patch with faces and the transform that brings its neighbour
//! patch's positions onto it (cyclicPolyPatch::calcTransforms and transformPosition).
struct CyclicPatch
{
    Index patch = -1;     //!< index in mesh.patches
    Index neighbour = -1; //!< index of its neighbourPatch
    //! The owner side holds the statistics of the pair (cyclicPolyPatch::owner).
    bool owner() const { return patch < neighbour; }
    //! forwardT: none, one for all faces, or one per face.
    std::vector<Eigen::Matrix3d> rotation;
    Vector3 rotation_centre = Vector3::Zero(); //!< only for `transform rotational`
    bool rotational = false;                   //!< `transform rotational`: rotate about the centre
    //! separation (neighbour face centre - own face centre): none, one, or one per face.
    std::vector<Vector3> separation;

    //! \brief A position from the neighbour side of face i, seen from this side.
    Vector3 transform_position(const Vector3& p, Index i) const;
};

//! \brief The cyclic and cyclicSlip patches with faces, in patch order, with their transforms
//! computed from the mesh's face centres and areas.
//! \throws InvalidInput if a neighbourPatch is missing or sizes or transforms do not match.
std::vector<CyclicPatch> cyclic_patches(const PolyMesh& mesh, const MeshGeometry& geometry);

//! \brief coupledPolyPatch::calcFaceTol for each face of patch `p`: the largest distance of a
//! vertex from the face centre, at least SMALL times the largest vertex coordinate (and SMALL).
std::vector<double> face_tolerances(const PolyMesh& mesh, const MeshGeometry& geometry,
                                    const Patch& p);

//! The faces checkMesh couples and what lies across them (syncTools'
//! getInternalOrCoupledFaces, getMasterFaces and swapBoundaryCellPositions/-List).
struct CoupledFaces
{
    //! per face: internal, or on a cyclic or processor patch
    std::vector<char> internal_or_coupled;
    //! per face: not on the non-owner side of a cyclic or processor patch
    std::vector<char> master;
    //! per boundary face (face - nInternalFaces): the cell centre across a cyclic face
    //! (transformed to this side) or processor face; the owner's centre on other faces.
    Points neighbour_cell_centres;
    Eigen::VectorXd neighbour_cell_volumes; //!< per boundary face, likewise (no transform)

    bool coupled_boundary(const PolyMesh& mesh, Index f) const
    {
        return !mesh.is_internal_face(f) && internal_or_coupled[static_cast<std::size_t>(f)];
    }
    //! Per face: the faces whose values enter checkMesh's min/max/average, the internal ones
    //! and the owner side of each cyclic (syncTools::getInternalOrMasterFaces).
    std::vector<char> statistics_faces() const;
};

//! \brief The coupled faces of `cyclics` (cyclic_patches(mesh, geometry)) and, in a -parallel
//! run, of the processor patches (`processors`, their owner side is the lower rank).
CoupledFaces coupled_faces(const PolyMesh& mesh, const MeshGeometry& geometry,
                           const std::vector<CyclicPatch>& cyclics,
                           const ProcessorFaces* processors = nullptr);

} // namespace meshmorph
