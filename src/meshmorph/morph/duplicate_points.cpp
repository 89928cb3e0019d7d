// SPDX-License-Identifier: GPL-3.0-or-later
// Duplicate prescribed points (see duplicate_points.h).
#include "meshmorph/morph/duplicate_points.h"

#include <algorithm>
#include <numeric>
#include <sstream>
#include <vector>

#include "meshmorph/core/exceptions.h"

namespace meshmorph::morph
{

namespace
{

std::string vector_text(const Eigen::RowVector3d& v)
{
    std::ostringstream s;
    s.precision(12);
    s << "(" << v(0) << " " << v(1) << " " << v(2) << ")";
    return s.str();
}

//! The patches whose faces use point p, "a/b" (only on the error path: a linear scan).
std::string patches_of(const PolyMesh& mesh, Index p)
{
    std::string names;
    for (const Patch& patch : mesh.patches)
        for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
        {
            const auto face = mesh.faces[f];
            if (std::find(face.begin(), face.end(), p) != face.end())
            {
                names += (names.empty() ? "" : "/") + patch.name;
                break;
            }
        }
    return names.empty() ? "no patch" : names;
}

} // namespace

void check_duplicate_prescribed_points(const PolyMesh& mesh, const Constraints& c,
                                       const std::string& points_file)
{
    const std::size_t n = c.points.size();
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t(0));
    const auto position = [&](std::size_t i) { return mesh.points.row(c.points[i]); };
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b)
              {
                  const auto pa = position(a), pb = position(b);
                  return std::lexicographical_compare(pa.begin(), pa.end(), pb.begin(), pb.end());
              });
    const double scale = c.displacements.rows() > 0 ? c.displacements.cwiseAbs().maxCoeff() : 0;
    for (std::size_t k = 1; k < n; ++k)
    {
        const std::size_t a = order[k - 1], b = order[k];
        if (position(a) != position(b))
            continue;
        const Eigen::RowVector3d da = c.displacements.row(Eigen::Index(a));
        const Eigen::RowVector3d db = c.displacements.row(Eigen::Index(b));
        if ((da - db).norm() <= 1e-12 * scale)
            continue;
        const Index pa = c.points[a], pb = c.points[b];
        throw InvalidInput(points_file + ": points " + std::to_string(pa) + " (" +
                           patches_of(mesh, pa) + ") and " + std::to_string(pb) + " (" +
                           patches_of(mesh, pb) + ") are duplicates at " +
                           vector_text(position(a)) + " but are prescribed different " +
                           "displacements " + vector_text(da) + " and " + vector_text(db) +
                           ": merge the duplicate points or fix the mesh (checkMeshQuality "
                           "-allGeometry lists close points)");
    }
}

} // namespace meshmorph::morph
