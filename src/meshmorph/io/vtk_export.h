// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A VTK data set as plain arrays: what vtk_writer.cpp prepares from a mesh and the
//! VTK module (vtk_module.cpp, `libmeshmorph_vtk.so`) turns into a VTK XML file.
//!
//! The applications load the module only when a run writes VTK: linking VTK's libraries
//! into them cost ~30 ms per start (their relocations and initialisers), twice for a
//! program that restarts itself with huge pages (app/process_memory.h), on every morph.
//! The interface is plain data and a function pointer, so the module needs nothing of
//! meshmorph's libraries (no second copy of their state).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace meshmorph::io
{

//! A named array of doubles: `tuples` x `components`, row-major.
struct VtkDoubles
{
    std::string name;
    int components = 1;
    std::int64_t tuples = 0;
    const double* values = nullptr;
};

//! VTK's vtkIdType (64-bit ids, checked by the module), so that the module hands the
//! arrays to VTK without copying them.
using VtkId = long long;

//! A named array of ids.
struct VtkIds
{
    std::string name;
    std::vector<VtkId> values;
};

struct VtkExport
{
    enum class Kind
    {
        unstructured_grid, //!< `.vtu`: cells with types, and face streams for polyhedra
        poly_data          //!< `.vtp`: polygons
    };
    Kind kind = Kind::unstructured_grid;
    std::int64_t n_points = 0;
    const double* points = nullptr; //!< n_points x 3, row-major
    //! Every array below, and those pointed to, must outlive the serialisation: the module
    //! lends them to VTK instead of copying them.
    //! The cells (unstructured grid) or polygons (poly data): offsets (one more than cells)
    //! into connectivity.
    std::vector<VtkId> offsets, connectivity;
    std::vector<unsigned char> cell_types; //!< unstructured grid: VTK cell type per cell
    //! Unstructured grid: per cell, the start of its face stream in `faces` or -1; empty
    //! when no cell is a polyhedron.
    std::vector<VtkId> face_locations, faces;
    std::vector<VtkIds> point_ids, cell_ids;
    std::vector<VtkDoubles> point_data, cell_data;
    std::vector<std::string> field_strings; //!< field data `PatchNames` (poly data), if any
};

//! The module's entry point: the file's bytes (binary appended, zlib) into `out`, or false
//! with the reason in `error`.
using VtkSerialise = bool (*)(const VtkExport& data, std::string& out, std::string& error);

//! The entry point's symbol in the module.
inline constexpr const char* vtk_serialise_symbol = "meshmorph_vtk_serialise";

} // namespace meshmorph::io
