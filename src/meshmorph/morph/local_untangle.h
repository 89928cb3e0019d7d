// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Local untangling: repair the few cells a morph inverts by moving interior points
//! near them, leaving every boundary point where the morph put it.
//!
//! A smooth field (RBF, IDW) can still fold a thin cell where a moving wall meets a fixed
//! one: at the motorBike's rear tyre, lifted off a fixed floor, one snappyHexMesh cell a
//! few millimetres thick lies almost in the tyre surface, and its one interior point lags
//! the tyre by more than its own distance from it. No step length avoids that, because the
//! fold is in the final field, not in the path. The repair is Freitag's "smart" Laplacian
//! smoothing, restricted to a neighbourhood of the invalid cells: each interior point there
//! whose cells are poor tries a few positions (towards the mean of its edge neighbours,
//! towards the mean of its cells' centres, its original position moved by the mean
//! displacement of its neighbours, and short steps up the quality's numerical gradient)
//! and takes the one that most raises the worst quality of the cells around it. The
//! quality is scale-free: the smallest cosine over those cells of (a) the angle between a
//! face's normal and the direction from the cell centre to the face centre (a face pyramid
//! is wrongly oriented when it is negative) and (b) the angle between an internal face's
//! normal and the owner-to-neighbour direction (non-orthogonality above 90 degrees when
//! negative). A point only moves when that minimum rises, so the repair never makes the
//! worst of its cells worse, and points whose cells are already good (cosine >= 0.2) stay
//! where the morph put them. The neighbourhood starts one layer of cells around the
//! invalid ones and doubles while cells remain invalid, up to max_layers.
//!
//! The repair stops with a margin, not at the edge of validity: it works on a cell until
//! its quality reaches its target, a cosine of 1e-3 (or the cell's quality in the original
//! mesh, if lower), so that checkMesh's verdict on the repaired cells does not hang on
//! round-off (another BLAS kernel or compiler moves the morph's points by ~1e-8 of the
//! motion). It watches every cell a moved point touches, not only its neighbourhood: a
//! move that raises the worst cell around a point may lower another.
#pragma once

#include <limits>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph::morph
{

//! The repair works on a cell until its quality reaches this cosine (every face pyramid and
//! internal face 0.06 degrees or more from the 90 degrees where checkMesh's verdict flips),
//! not merely until checkMesh would pass it: a cell left at a cosine of 1e-12 passes or
//! fails on the last bits of its points, which another BLAS kernel, compiler or thread
//! count changes. A relative volume of 1e-3 is ten orders of magnitude above that
//! round-off, so the verdict after the repair is the same on every machine.
inline constexpr double repair_margin_cosine = 1e-3;

//! The repair target of a cell invalid in the unmorphed mesh: below every quality, so the
//! repair never works on it.
inline constexpr double repair_left_alone = -3.0;

//! A repair target meaning "the cell's quality as the morph left it" (untangle_cells).
inline constexpr double repair_target_now = std::numeric_limits<double>::quiet_NaN();

struct UntangleSettings
{
    int max_layers = 8; //!< the widest neighbourhood, in layers of cells around the invalid ones
    int sweeps = 40;    //!< passes over the neighbourhood's points, per neighbourhood
};

//! What a repair raises its cells to. The default is the untangling's: the smallest
//! cosine of (a) and (b) above, points left alone whose cells are all above 0.2 (78
//! degrees). The repair of severely non-orthogonal faces (non_ortho_repair.h) weights the
//! pyramids' cosines up so that the orthogonality's decides until a pyramid nears the margin.
struct RepairGoal
{
    double pyramid_weight = 1.0; //!< the face pyramids' cosines are multiplied by this
    double good_enough = 0.2;    //!< a point whose cells are all at least this stays
};

struct UntangleReport
{
    Index invalid_before = 0;     //!< cells invalid (and not in the original mesh) on entry
    Index invalid_after = 0;      //!< cells it watched that checkMesh counts invalid on return
    Index below_target_after = 0; //!< cells it watched still below their target on return
    Index points_moved = 0;       //!< distinct interior points moved
    int layers = 0;               //!< the neighbourhood's width when the repair stopped
    double max_move = 0.0;        //!< the largest distance a point was moved
    //! Not tried (all else 0): the cells below their target, more than the caller's limit.
    Index skipped_cells = 0;
};

//! \brief The repair's quality of cell c: the smallest of its face pyramids' cosines (times
//! `pyramid_weight`) and its internal faces' orthogonality cosines; below -1 when its volume
//! is not positive.
double repair_quality(const PolyMesh& mesh, const CompactList& cell_faces, const MeshGeometry& g,
                      Index c, double pyramid_weight = 1.0);

//! \brief Per cell: 1 when it has a volume below OpenFOAM's VSMALL, a wrongly oriented face
//! pyramid or an internal face whose non-orthogonality reaches 90 degrees.
std::vector<char> invalid_cell_flags(const PolyMesh& mesh, const CompactList& cell_faces,
                                     const MeshGeometry& geometry);

//! \brief Per cell of the unmorphed mesh, the quality the repair raises it to when a morph
//! takes it below: the smaller of the margin (cosine 1e-3) and its own quality there; a
//! cell invalid in the unmorphed mesh gets a target below every quality (left alone).
std::vector<double> repair_targets(const PolyMesh& original, const CompactList& cell_faces,
                                   const MeshGeometry& geometry);

//! \brief The cells below their repair target in `mesh` (those untangle_cells() starts
//! from), counted in one pass over the cells.
Index count_cells_below_target(const PolyMesh& mesh, const CompactList& cell_faces,
                               const MeshGeometry& geometry, const std::vector<double>& targets,
                               double pyramid_weight = 1.0);

//! \brief Repair the cells that are below their target in `mesh`.
//! \param mesh the morphed mesh; its interior points near those cells are moved.
//! \param geometry compute_geometry(mesh, cell_faces) on entry; kept up to date.
//! \param original_points the mesh before the morph (for the displacement candidate).
//! \param targets repair_targets of the original mesh; an entry repair_target_now (NaN) is the
//! cell's quality when the repair first looks at it, capped at goal.good_enough (only with
//! `start`: the pass that finds the cells below their targets needs them all).
//! \param movable per point, 1 when the repair may move it (interior points).
//! \param start the cells below their target, when the caller knows them (else one pass).
UntangleReport untangle_cells(PolyMesh& mesh, const CompactList& cell_faces, MeshGeometry& geometry,
                              const Points& original_points, const std::vector<double>& targets,
                              const std::vector<char>& movable, const UntangleSettings& settings,
                              const RepairGoal& goal = {},
                              const std::vector<Index>* start = nullptr);

} // namespace meshmorph::morph
