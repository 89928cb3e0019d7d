// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A triangle surface (vertices + triangles) and an AABB tree for closest-point
//! queries (morphMesh's `surface` boundary type projects points onto it). The STL and OBJ
//! readers are in io/surface_io.h.
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/types.h"

namespace meshmorph
{

//! m x 3 vertex labels per triangle; counter-clockwise seen from the side the normal points to.
using Triangles = Eigen::Matrix<Index, Eigen::Dynamic, 3, Eigen::RowMajor>;

//! A triangle surface: plain data.
struct TriangleSurface
{
    Points vertices;     //!< n x 3
    Triangles triangles; //!< m x 3, labels in [0, n)

    Index n_vertices() const { return static_cast<Index>(vertices.rows()); }
    Index n_triangles() const { return static_cast<Index>(triangles.rows()); }
};

//! The result of a closest-point query.
struct SurfacePoint
{
    Vector3 point = Vector3::Zero();                           //!< closest point on the surface
    Index triangle = -1;                                       //!< triangle containing it
    double distance = std::numeric_limits<double>::infinity(); //!< |query - point|
};

//! \brief Closest point on one triangle (a, b, c) to q, by Voronoi regions (Ericson,
//! Real-Time Collision Detection, §5.1.5). Degenerate triangles are handled (their closest
//! edge point is returned).
Vector3 closest_point_on_triangle(const Vector3& q, const Vector3& a, const Vector3& b,
                                  const Vector3& c);

//! An axis-aligned bounding-box tree over the triangles of a surface for exact closest-point
//! queries. Built once (median split on the longest axis, up to 4 triangles per leaf); queries
//! are const and thread-safe.
class SurfaceTree
{
public:
    //! \throw InvalidInput if the surface has no triangles, a label is out of range or a
    //! coordinate is not finite.
    explicit SurfaceTree(TriangleSurface surface);

    //! \brief The closest surface point to query (exact). When the surface has another
    //! place as near as the nearest, to within tie_tolerance() (a wall point equally near
    //! two slopes of a target, e.g. on a venturi's plane of symmetry), the place of the
    //! triangle listed first in the surface wins, and within it the exact nearest point;
    //! without the rule the point went to whichever slope the last bit of the arithmetic
    //! favoured: up or down the pipe, depending on the processor and the build. Neighbouring
    //! triangles near an edge are one place, not a tie (the exact nearest point is returned).
    SurfacePoint closest_point(const Vector3& query) const;

    //! \brief Distances closer than this count as equal: 1e-9 of the surface's size (its
    //! bounding box diagonal, or its largest coordinate if larger), far above the round-off
    //! of a distance (1e-16 relative) and far below any geometric difference that matters.
    double tie_tolerance() const { return tie_tolerance_; }

    //! \brief Closest points for every row of queries (k x 3), OpenMP over queries.
    Points closest_points(const Eigen::Ref<const Points>& queries) const;

    const TriangleSurface& surface() const { return surface_; }

private:
    struct Node
    {
        Eigen::Vector3d lo, hi;
        Index first = 0; //!< leaf: first entry of order_; inner: left child (right = first + 1)
        Index count = 0; //!< leaf: number of triangles; inner: 0
    };
    void build(Index node, Index begin, Index end, const std::vector<Eigen::Vector3d>& centroids);

    TriangleSurface surface_;
    std::vector<Node> nodes_;
    std::vector<Index> order_; //!< triangle labels, leaf ranges contiguous
    double tie_tolerance_ = 0.0;
};

} // namespace meshmorph
