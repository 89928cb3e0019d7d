// SPDX-License-Identifier: GPL-3.0-or-later
//! \file VTK XML export (ParaView): the volume mesh as `.vtu`, boundary patches as `.vtp`.
//!
//! Files are VTK XML, binary appended data compressed with zlib, 64-bit headers, written
//! through VTK's own writers and atomically (temporary file in the same directory, then
//! rename). Only built when VTK is found (MESHMORPH_WITH_VTK).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph::io
{

//! A named array attached to the points or cells of a VTK file: n rows x k components
//! (k = 1 scalars, k = 3 vectors such as a displacement).
struct VtkField
{
    using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

    std::string name;
    Matrix values;

    VtkField() = default;
    //! n x k values from any Eigen expression: an Eigen::VectorXd of n scalars (n x 1), an
    //! n x 3 Points displacement, ... (copied).
    template <class Derived>
    VtkField(std::string field_name, const Eigen::MatrixBase<Derived>& matrix)
        : name(std::move(field_name)), values(matrix)
    {
    }
};

//! \brief Write the volume mesh as a VTK XML unstructured grid (`.vtu`).
//!
//! Cells are native VTK_HEXAHEDRON, VTK_WEDGE (OpenFOAM prism), VTK_PYRAMID and VTK_TETRA
//! where the cell has that topology (core/cell_shapes.h vtk_cell), and VTK_POLYHEDRON with an
//! outward face stream otherwise (OpenFOAM wedges, tet-wedges, general polyhedra). All mesh
//! points are written in mesh order, so point p of the file is mesh point p and cell c is
//! mesh cell c. A cell-data array `cellID` (mesh cell label) is always written.
//! \param path output file (conventionally `.vtu`); its directory must exist.
//! \param mesh the mesh (points nPoints x 3).
//! \param point_data arrays with nPoints rows each. \param cell_data arrays with nCells rows.
//!        Values may be NaN (e.g. a metric undefined for a cell); VTK stores them as is.
//! \throw InvalidInput on a row-count mismatch, or an empty, duplicate or reserved (`cellID`)
//!        name.
//! \throw IoError naming the path when writing or renaming fails (no partial file is left).
void write_vtu(const std::filesystem::path& path, const PolyMesh& mesh,
               const std::vector<VtkField>& point_data = {},
               const std::vector<VtkField>& cell_data = {});

//! \brief Write boundary patches as VTK XML poly data (`.vtp`): one polygon per face, with
//! the face loop as stored (normal pointing out of the domain).
//!
//! Points are the patches' vertices, renumbered compactly in order of first appearance;
//! point-data array `pointID` holds the mesh point label of each. Cell data: `patchID`
//! (index into mesh.patches) and `faceID` (mesh face label). Field data: `PatchNames`
//! (string array indexed by patchID, all patches of the mesh).
//! \param patches patch indices to write (in this order); empty = every patch.
//! \param point_data arrays with nPoints (mesh) rows; the rows of the written points are
//!        extracted. \param face_data arrays with one row per written face, in output order
//!        (patch by patch as listed, faces in mesh order).
//! \throw InvalidInput on a bad patch index, a row-count mismatch, or an empty, duplicate or
//!        reserved (`pointID`, `patchID`, `faceID`) name.
//! \throw IoError naming the path when writing fails.
void write_vtp_patches(const std::filesystem::path& path, const PolyMesh& mesh,
                       const std::vector<Index>& patches = {},
                       const std::vector<VtkField>& point_data = {},
                       const std::vector<VtkField>& face_data = {});

} // namespace meshmorph::io
