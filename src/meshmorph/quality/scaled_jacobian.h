// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Scaled Jacobian cell quality (the paper's mesh-quality measure, Fig. 14).
//!
//! The scaled Jacobian of a corner is the determinant of its three edge vectors, each
//! normalised to unit length; a cell's value is the minimum over its corners, so it lies in
//! [-1, 1] (up to the per-shape normalisation below), is 1 for a cube, a box or a regular
//! tetrahedron, 0 for a degenerate and negative for an inverted cell, and does not depend on
//! scale. Definitions follow Verdict (Stimpson et al., "The Verdict Geometric Quality
//! Library", SAND2007-1751), as used by vtkMeshQuality:
//! - hexahedron: minimum over the 8 corners and the centre (the principal axes) of the
//!   normalised Jacobian (verdict hex_scaled_jacobian);
//! - tetrahedron: sqrt(2) * 6V / (largest product of the three edge lengths at a vertex)
//!   (verdict tet_scaled_jacobian);
//! - prism (VTK wedge): minimum over the 6 corners, times 2/sqrt(3) so that the right prism
//!   with equilateral ends is 1;
//! - pyramid: minimum over the 4 base corners (base edges and the edge to the apex), times
//!   sqrt(2) so that the pyramid with a square base and equilateral sides is 1.
//! Hexahedra and tetrahedra match vtkMeshQuality (VTK 9.1) to rounding; VTK 9.1 has no prism
//! or pyramid scaled Jacobian, so those follow the later Verdict definitions and are tested by
//! their properties. Where Verdict returns DBL_MAX for a zero-length edge, these return 0.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/cell_shapes.h"
#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! \brief Scaled Jacobian of a hexahedron, vertices in VTK_HEXAHEDRON order.
double hex_scaled_jacobian(const std::array<Vector3, 8>& p);
//! \brief Scaled Jacobian of a tetrahedron, vertices in VTK_TETRA order.
double tet_scaled_jacobian(const std::array<Vector3, 4>& p);
//! \brief Scaled Jacobian of a triangular prism, vertices in VTK_WEDGE order.
double prism_scaled_jacobian(const std::array<Vector3, 6>& p);
//! \brief Scaled Jacobian of a pyramid, vertices in VTK_PYRAMID order (apex last).
double pyramid_scaled_jacobian(const std::array<Vector3, 5>& p);

//! \brief The corners the scaled Jacobian reads: per cell its VTK type and up to 8 point
//! labels in VTK order (unused slots -1). Topology only, and the costly part (matching each
//! cell's faces to a model cell): computed once, it serves every later position of the same
//! mesh's points, such as morphMesh's check after a morph.
struct JacobianCorners
{
    std::vector<VtkCellType> types;           //!< nCells; polyhedron: no value (NaN)
    std::vector<std::array<Index, 8>> points; //!< nCells
};

//! \brief The cells' corners (see JacobianCorners).
//! \throw InvalidInput if shapes and cell_faces differ in size.
JacobianCorners jacobian_corners(const PolyMesh& mesh, const CompactList& cell_faces,
                                 const std::vector<CellShape>& shapes);

//! \brief Scaled Jacobian of every cell from its corners at the mesh's current points.
//! \throw InvalidInput if the corners are not of mesh's cells (sizes differ).
Eigen::VectorXd scaled_jacobian(const PolyMesh& mesh, const JacobianCorners& corners);

//! \brief Scaled Jacobian of every cell.
//!
//! Cells whose topology is a hexahedron, tetrahedron, prism or pyramid (core/cell_shapes.h
//! vtk_cell gives them a native VTK type) get the value above; every other cell (OpenFOAM
//! wedges and tet-wedges, polyhedra, malformed cells) gets NaN.
//! \param mesh the mesh. \param cell_faces from meshmorph::cell_faces(mesh).
//! \param shapes from classify_cells(mesh, cell_faces).
//! \return nCells values, NaN where undefined.
//! \throw InvalidInput if shapes and cell_faces differ in size.
Eigen::VectorXd scaled_jacobian(const PolyMesh& mesh, const CompactList& cell_faces,
                                const std::vector<CellShape>& shapes);

//! \brief Convenience overload computing the cell faces and shapes.
Eigen::VectorXd scaled_jacobian(const PolyMesh& mesh);

} // namespace meshmorph
