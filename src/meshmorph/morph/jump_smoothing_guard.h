// SPDX-License-Identifier: GPL-3.0-or-later
//! \file `jumpSmoothing auto`: the smoothing kept only where it makes the band's cells better.
//!
//! The Laplacian of the band (jump_smoothing.h) spreads the shear of a jump over the cells
//! between a moving wall and a fixed one. Where those cells are graded (small by the fixed
//! wall), it can concentrate the shear in the small cells instead: on the tutorials' meshes
//! with a scaled wall patch it raised the largest non-orthogonality about as often as it
//! lowered it. So the default compares the two fields on the cells the band touches, after
//! each step's fit and before its check: the cells that are not valid (negative volume)
//! first, then the largest non-orthogonality of their faces (checkMesh's measure, the
//! figure the smoothing aims to lower). The smoothed field is kept only if it has no more
//! invalid cells and lowers that maximum by more than `margin_degrees`; otherwise the
//! fitted field is put back. Both fields are exact at every constrained point, so either
//! choice keeps the morph exact.
#pragma once

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/jump_smoothing.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::morph
{

//! The band's cells under one field.
struct BandQuality
{
    Index invalid_cells = 0;    //!< cells touching the band with a volume not above 0
    double max_non_ortho = 0.0; //!< the largest non-orthogonality of their faces [deg]
    Index faces_above_70 = 0;   //!< of those faces, above 70 degrees (for the log)
};

//! What the guard compared and chose.
struct JumpSmoothingChoice
{
    bool compared = false; //!< false: no band, nothing to choose
    bool kept = false;
    BandQuality smoothed, fitted;
};

//! A smaller improvement than this is no reason to keep the smoothing: 1e-3 degrees is far
//! above the round-off of an angle (about 1e-10 degrees), so that the choice does not hang
//! on the BLAS kernel or the thread count, and far below what a user reads in checkMesh.
constexpr double margin_degrees = 1e-3;

//! \brief Keep the smoothed band or put the fitted field back (see the file comment).
//! \param trial the mesh with the smoothed field applied (accepted + displacement);
//! \param geometry its geometry; \param accepted the points the step started from;
//! \param s the smoothing (its band and the fitted values); \param displacement the step's
//! field (smoothed). On return trial, geometry and displacement hold the choice. In a
//! -parallel run a collective: the figures are reduced over every rank, and the processor
//! faces beside a band cell on either side are measured against the cell across, as
//! checkMesh -parallel does, so the choice is the serial one.
JumpSmoothingChoice choose_jump_smoothing(PolyMesh& trial, const CompactList& cell_faces,
                                          MeshGeometry& geometry, const Points& accepted,
                                          const JumpSmoothing& s, Points& displacement,
                                          const parallel::Communicator& comm);

} // namespace meshmorph::morph
