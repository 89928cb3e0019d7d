// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Cell shape recognition (OpenFOAM's cellMatcher) and VTK cell connectivity.
//!
//! classify_cells() reproduces the "Overall number of cells of each type" block of
//! OpenFOAM v1912's checkMesh (docs/checkmesh-spec.md §3.1): the matchers are tried in the
//! order hex, tet, pyramid, prism, wedge, tet-wedge, each in its `isA` (check-only) form.
//! vtk_cell() runs the full matchers to recover the model's vertex order, which is what a
//! VTK file needs.
#pragma once

#include <cstdint>
#include <map>
#include <string_view>
#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph
{

//! The cell classes checkMesh counts. `wedge` is OpenFOAM's degenerate hex (7 vertices),
//! `prism` the ordinary triangular prism, `tet_wedge` OpenFOAM's 5-vertex tetWedge.
enum class CellShape : std::uint8_t
{
    hex,
    prism,
    wedge,
    pyramid,
    tet_wedge,
    tet,
    polyhedron
};

//! checkMesh's name of a shape ("hexahedra", "prisms", "wedges", "pyramids", "tet wedges",
//! "tetrahedra", "polyhedra").
std::string_view checkmesh_name(CellShape shape);

//! \brief The shape class of every cell, as OpenFOAM v1912's checkMesh counts it.
//!
//! Face-count tests follow OpenFOAM exactly: hex = 6 quads, tet = 4 triangles and pyramid =
//! 4 triangles + 1 quad are accepted on face sizes alone (OpenFOAM's `isA` does not walk these
//! shapes); prism (2 triangles + 3 quads, 6 distinct vertices, a quad and then the other
//! triangle reached across the first triangle's edge), wedge (2 triangles + 4 quads, 7
//! distinct vertices) and tet-wedge (2 triangles + 2 quads) as in OpenFOAM's matchers.
//! Where OpenFOAM would abort or read out of range (an edge used by 3 faces of the cell, or an
//! open cell) the matcher reports "no match" and the cell falls through to the next class.
//! \param mesh the mesh (only `faces` and `owner` are read).
//! \param cell_faces nCells lists of face labels, from meshmorph::cell_faces(mesh) (the face
//!        order matters for the walk, as in OpenFOAM).
//! \return nCells shapes.
//! \pre face labels in cell_faces are in [0, nFaces).
std::vector<CellShape> classify_cells(const PolyMesh& mesh, const CompactList& cell_faces);

//! checkMesh's counters: one per class, and for polyhedra the number of cells per face count.
struct CellShapeCounts
{
    Index hex = 0;
    Index prism = 0;
    Index wedge = 0;
    Index pyramid = 0;
    Index tet_wedge = 0;
    Index tet = 0;
    Index polyhedron = 0;
    //! number of faces -> number of polyhedral cells with that many faces (ascending keys,
    //! the "Breakdown of polyhedra by number of faces" table).
    std::map<Index, Index> polyhedra_by_faces;

    Index count(CellShape shape) const;
    bool operator==(const CellShapeCounts&) const = default;
};

//! \brief Count shapes as checkMesh prints them.
//! \param shapes nCells shapes from classify_cells. \param cell_faces nCells face lists.
//! \throw InvalidInput if the sizes differ.
CellShapeCounts count_cell_shapes(const std::vector<CellShape>& shapes,
                                  const CompactList& cell_faces);

//! VTK cell type ids (the values of vtkCellType.h), so that core needs no VTK headers.
enum class VtkCellType : std::uint8_t
{
    tetra = 10,
    hexahedron = 12,
    wedge = 13,
    pyramid = 14,
    polyhedron = 42
};

//! One cell in VTK's terms.
struct VtkCell
{
    VtkCellType type = VtkCellType::polyhedron;
    //! Vertex labels (mesh point labels). Linear cells: VTK's vertex order, oriented so that
    //! VTK computes a positive volume for a valid cell. Polyhedron: the cell's distinct points
    //! in order of first appearance.
    std::vector<Index> points;
    //! Polyhedron only (else empty): VTK's face stream
    //! `nFaces, n0, p0_0 .. p0_{n0-1}, n1, ...` with mesh point labels, every face oriented
    //! outwards (neighbour faces reversed).
    std::vector<Index> face_stream;
};

//! \brief VTK connectivity of one cell.
//!
//! Hexahedra, tetrahedra, pyramids and prisms whose faces form the model's topology (the full
//! OpenFOAM matcher succeeds, with the right number of distinct vertices) become the native
//! VTK cells VTK_HEXAHEDRON, VTK_TETRA, VTK_PYRAMID and VTK_WEDGE (OpenFOAM's prism; vertex
//! order 0 2 1 3 5 4 as foamToVTK writes it). Everything else, including OpenFOAM's wedge and
//! tet-wedge, becomes VTK_POLYHEDRON with a face stream.
//! \param mesh the mesh. \param cell_faces from meshmorph::cell_faces(mesh).
//! \param cell cell label in [0, nCells). \param shape classify_cells()'s result for the cell.
//! \throw InvalidInput if cell is out of range.
VtkCell vtk_cell(const PolyMesh& mesh, const CompactList& cell_faces, Index cell, CellShape shape);

//! \brief vtk_cell() into caller-owned buffers (cleared first), for loops over many cells
//! without allocating. \return the cell type.
VtkCellType vtk_cell(const PolyMesh& mesh, const CompactList& cell_faces, Index cell,
                     CellShape shape, std::vector<Index>& points, std::vector<Index>& face_stream);

//! \brief VTK connectivity of every cell, in the flat layout vtkUnstructuredGrid uses.
struct VtkCells
{
    std::vector<VtkCellType> types; //!< nCells
    CompactList points;             //!< nCells point lists (see VtkCell::points)
    CompactList face_streams;       //!< nCells face streams, empty for linear cells
};

//! \brief vtk_cell() for all cells. \param shapes from classify_cells (nCells entries).
//! \throw InvalidInput if sizes differ.
VtkCells vtk_cells(const PolyMesh& mesh, const CompactList& cell_faces,
                   const std::vector<CellShape>& shapes);

} // namespace meshmorph
