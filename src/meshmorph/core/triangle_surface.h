// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A triangle surface (vertices + triangles): STL/OBJ readers and an AABB tree for
//! closest-point queries (morphMesh's `surface` boundary type projects points onto it).
#pragma once

#include <filesystem>
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

//! \brief Read an STL file, ASCII or binary (told apart by the binary size rule
//! 84 + 50 m bytes, since binary headers may also start with "solid"); all solids of an ASCII
//! file are concatenated. Vertices with identical coordinates are merged, so the result is
//! indexed (STL itself is a triangle soup). Facet normals are ignored: the vertex order gives
//! the orientation. A `.gz` file is decompressed.
//! \throw IoError if the file cannot be read.
//! \throw ParseError naming the file and line (ASCII) or byte offset (binary) on malformed
//!        content: unexpected keyword, bad or non-finite number, truncated data, no triangles.
TriangleSurface read_stl(const std::filesystem::path& path);

//! \brief Read a Wavefront OBJ file: `v x y z [w]` and `f` lines (`i`, `i/t`, `i//n`, `i/t/n`,
//! negative = relative indices); polygons are fan-triangulated from their first vertex; other
//! statements (vn, vt, g, o, s, usemtl, mtllib, l, ...) are ignored. A `.gz` file is
//! decompressed.
//! \throw IoError if unreadable. \throw ParseError (file:line) on a malformed number, an index
//!        out of range, a face with fewer than 3 vertices, or no faces at all.
TriangleSurface read_obj(const std::filesystem::path& path);

//! \brief read_stl or read_obj by extension (`.stl`, `.obj`, case-insensitive, optionally
//! followed by `.gz`). \throw InvalidInput for another extension (message lists the supported
//! ones), else as the readers.
TriangleSurface read_surface(const std::filesystem::path& path);

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

    //! \brief The closest surface point to query (exact; ties go to the lowest-visited triangle).
    SurfacePoint closest_point(const Vector3& query) const;

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
};

} // namespace meshmorph
