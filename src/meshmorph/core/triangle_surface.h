// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A triangle surface (vertices + triangles), e.g. an STL/OBJ target or a triangulated
//! boundary patch.
#pragma once

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

} // namespace meshmorph
