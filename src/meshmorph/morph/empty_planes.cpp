// SPDX-License-Identifier: GPL-3.0-or-later
// The empty planes of 2D cases: found from the empty patches, used to keep a morph 2D.
#include "meshmorph/morph/empty_planes.h"

#include "meshmorph/core/exceptions.h"
#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph::morph
{

Points EmptyPlanes::project(const Points& x) const
{
    Points out = x;
    const Eigen::VectorXd distance = (x * normal).array() - offset;
    out -= distance * normal.transpose();
    return out;
}

void EmptyPlanes::remove_normal(Points& d) const
{
    const Eigen::VectorXd along = d * normal;
    d -= along * normal.transpose();
}

std::optional<EmptyPlanes> find_empty_planes(const PolyMesh& mesh)
{
    std::optional<EmptyPlanes> planes;
    for (const Patch& patch : mesh.patches)
    {
        if (patch.type != "empty")
            continue;
        for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
        {
            const Vector3 a = face_area_vector(mesh, f);
            if (a.norm() <= constants::vsmall)
                continue;
            const Vector3 n = a.normalized();
            if (!planes)
                planes = EmptyPlanes{n, n.dot(mesh.points.row(mesh.faces[f][0]).transpose())};
            else if (n.cross(planes->normal).norm() > 1e-6)
                throw InvalidInput("empty patch '" + patch.name +
                                   "' is not parallel to the other empty planes: morphMesh "
                                   "keeps 2D cases 2D only when they are extruded along one "
                                   "direction");
        }
    }
    return planes;
}

Vector3 evaluation_position(const std::optional<EmptyPlanes>& planes, const Vector3& x)
{
    return planes ? planes->project(x) : x;
}

Vector3 in_plane(const std::optional<EmptyPlanes>& planes, const Vector3& d)
{
    return planes ? planes->in_plane(d) : d;
}

} // namespace meshmorph::morph
