// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Discrete mean curvature of triangle surfaces and boundary patches (paper §3.3).
//!
//! The paper's smoothness measure: H(x_i) = 1/2 |Δx_i| with the cotangent discretisation of
//! the Laplace-Beltrami operator \cite Meyer2003 ("Discrete Differential-Geometry Operators
//! for Triangulated 2-Manifolds", Meyer, Desbrun, Schröder, Barr):
//!   Δx_i = 1/(2 A_mixed(i)) Σ_j (cot α_ij + cot β_ij) (x_j − x_i),
//! where α_ij, β_ij are the angles opposite edge ij and A_mixed is Meyer's mixed area (the
//! Voronoi area inside non-obtuse triangles; half or a quarter of the triangle area for
//! obtuse ones). Δx_i = −2 H n, so |Δx_i| / 2 is the unsigned mean curvature (1/R on a sphere
//! of radius R, 1/(2R) on a cylinder, 0 on a plane).
//! Used by the paper benchmark's Sec. 3.2 and 3.3 (benchmarks/paper/quality.cpp,
//! robustness.cpp) and by benchVtkExport.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/triangle_surface.h"

namespace meshmorph
{

//! \brief Laplace-Beltrami of the vertex positions, Δx_i (n x 3, the mean-curvature normal
//! −2 H n), by cotangent weights and mixed areas (Meyer et al. 2003, Eq. 8 and Fig. 4).
//!
//! Vertices on the surface border (on an edge used by a single triangle), on no triangle,
//! or whose mixed area is zero get NaN rows: the formula assumes a closed one-ring.
//! Degenerate triangles (zero area) contribute nothing.
//! \param vertices n x 3. \param triangles m x 3 labels in [0, n).
//! \throw InvalidInput on a label out of range.
Points laplace_beltrami(const Eigen::Ref<const Points>& vertices, const Triangles& triangles);

//! \brief Mean curvature H(x_i) = 1/2 |Δx_i| per vertex (n values; NaN where
//! laplace_beltrami is NaN). \throw InvalidInput on a label out of range.
Eigen::VectorXd mean_curvature(const Eigen::Ref<const Points>& vertices,
                               const Triangles& triangles);

//! \brief mean_curvature of a TriangleSurface.
Eigen::VectorXd mean_curvature(const TriangleSurface& surface);

//! How triangulate_patches splits faces with more than 3 vertices.
enum class PolygonSplit
{
    //! No new vertices: a quad along its shorter diagonal, a larger polygon as a fan from the
    //! first vertex from which every fan triangle faces the same way as the polygon (convex
    //! and star-shaped polygons), otherwise (no such vertex) a fan around its vertex average. Every
    //! vertex then lies on the surface sampled by the mesh, so curvature converges with refinement
    //! (default).
    diagonals,
    //! Every polygon as a fan around its vertex average (an extra vertex per face). On a
    //! curved surface the average lies off the surface by O(h^2), which bends the fan by
    //! O(1/R): the curvature error does not vanish with refinement. For display only.
    centre_fan
};

//! \brief Triangulate boundary patches: triangles are kept, other faces are split as
//! `split` says. \param patches patch indices (empty = all). \return vertices = all mesh
//! points followed by any added centres (so vertex p < nPoints is mesh point p), triangles
//! oriented like their faces (out of the domain).
//! \throw InvalidInput on a bad patch index, face label or a face with fewer than 3 vertices.
TriangleSurface triangulate_patches(const PolyMesh& mesh, const std::vector<Index>& patches = {},
                                    PolygonSplit split = PolygonSplit::diagonals);

//! \brief Mean curvature at every mesh point of the union of the given boundary patches
//! (triangulate_patches, then mean_curvature).
//! \return nPoints values: NaN for points not on those patches and on the border of their
//! union (e.g. the rim of a single face of a box); ready for io::write_vtp_patches point data.
Eigen::VectorXd patch_mean_curvature(const PolyMesh& mesh, const std::vector<Index>& patches = {},
                                     PolygonSplit split = PolygonSplit::diagonals);

} // namespace meshmorph
