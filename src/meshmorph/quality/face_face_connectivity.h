// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Face-face connectivity (OpenFOAM primitiveMesh::checkFaceFaces): faces sharing all
//! points with another face, and faces whose shared points with another face are not one
//! consecutive run on both.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! Per face f, what it shares with each higher face g that has a point in common.
struct FaceFaceConnectivity
{
    std::vector<Index> baffles;     //!< nFaces: higher faces with the same points (f == g)
    std::vector<Index> duplicates;  //!< nFaces: higher faces with all of f's or all of g's
                                    //!< points but of another size
    std::vector<char> order_errors; //!< nFaces: some shared run is not consecutive
    //! nFaces: in a pair of faces that are duplicates, baffles or not consecutive on each
    //! other (both faces of the pair: checkMesh's edgeFaces set).
    std::vector<char> in_pair;
};

//! \brief Scan every pair of faces sharing a point. \param point_faces point_faces(mesh).
//! OpenMP over faces.
FaceFaceConnectivity face_face_connectivity(const PolyMesh& mesh, const CompactList& point_faces);

} // namespace meshmorph
