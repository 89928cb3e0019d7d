// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The repair of severely non-orthogonal faces a morph makes.
//!
//! Where a moving patch meets a fixed one, the prescription jumps along their shared edge,
//! and the few cells between them shear: on the motorBike lifted off its fixed floor, eight
//! faces of the cells under the tyres' contact go above 70 degrees (checkMesh's "severely
//! non-orthogonal"), whatever the smooth field (moveMesh's Laplacian gives 75 degrees there
//! at the same boundary motion). Their boundary points are prescribed, so no field through
//! them does better; moving the few interior points of those cells does. So after a step is
//! valid, the cells with a face it took above `maxNonOrtho` (a cell already beyond it in
//! the unmorphed mesh: more than 1 degree worse) get the untangling's smart Laplacian smoothing
//! (local_untangle.h) with another goal: the orthogonality cosine of their internal faces raised to
//! cos(limit
//! - 1 degree), or to the cell's own in the unmorphed mesh if lower, while every face
//! pyramid keeps the untangling's margin (the pyramids' cosines weighted so that they only
//! bind near it). Boundary points never move, so the morph stays exact. The 1 degree margin
//! keeps the count of faces above the limit from hanging on round-off.
//!
//! In a -parallel run a rank sees only its own cells: points of cells with a processor face
//! stay (a processor face's orthogonality is measured against the cell across), so a repair
//! next to the decomposition's cut may differ from the serial one.
#pragma once

#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph::morph
{

//! The margin below the limit the repair aims for, in degrees.
inline constexpr double non_ortho_margin_degrees = 1.0;

struct NonOrthoRepair
{
    Index cells = 0;       //!< cells with a face above the limit (new or worse) on entry
    Index cells_after = 0; //!< of the cells it watched, those still above on return
    Index points_moved = 0;
    double max_move = 0.0;
    Index skipped_cells = 0; //!< not tried (all else 0): more cells than the caller's limit
    double seconds = 0.0;
};

//! \brief The cells of the internal faces above the limit (in the morphed `mesh`), sorted:
//! one pass over the faces. A morph with none needs no repair.
std::vector<Index> cells_beyond_limit(const PolyMesh& mesh, const MeshGeometry& geometry,
                                      double limit_degrees);

//! \brief The repair's quality (repair_quality, the pyramids weighted) of `cells`.
std::vector<double> non_ortho_quality(const PolyMesh& mesh, const CompactList& cell_faces,
                                      const MeshGeometry& geometry, const std::vector<Index>& cells,
                                      double limit_degrees);

//! The cells beyond the limit, their quality now and in the unmorphed mesh.
struct NonOrthoCells
{
    std::vector<Index> cells;    //!< cells_beyond_limit of the morphed mesh
    std::vector<double> now;     //!< per cell: its quality in the morphed mesh
    std::vector<double> before;  //!< per cell: unmorphed (repair_left_alone: invalid there)
    std::vector<Index> repaired; //!< the cells that were better unmorphed: the repair's work
};

//! \brief Fill `before` and `repaired` of `cells` from `original` (same topology, the
//! unmorphed points); only the geometry of those cells and their neighbours is computed. A
//! cell checkMesh counts invalid unmorphed is left alone, as the untangling leaves it.
void assess_non_orthogonal_cells(const PolyMesh& original, const CompactList& cell_faces,
                                 double limit_degrees, NonOrthoCells& cells);

//! \brief Repair in place `cells.repaired`, moving interior points near them (geometry kept
//! current); `original_points`: the unmorphed points. The report's counts are local (the
//! caller sums them over the ranks); `cells` and `seconds` are not set.
NonOrthoRepair repair_non_orthogonality(PolyMesh& mesh, const CompactList& cell_faces,
                                        MeshGeometry& geometry, const Points& original_points,
                                        const NonOrthoCells& cells, double limit_degrees);

} // namespace meshmorph::morph
