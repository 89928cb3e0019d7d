// SPDX-License-Identifier: GPL-3.0-or-later
// OpenFOAM's planarity test of symmetryPlane patches.
#include "meshmorph/quality/symmetry_plane_planarity.h"

#include <algorithm>
#include <cstdint>

#include "meshmorph/mesh/mesh_geometry.h"

namespace meshmorph
{

namespace
{

//! Unit normals of a patch's faces, as OpenFOAM's faceNormals (area / (|area| + VSMALL)).
std::vector<Vector3> unit_normals(const PolyMesh& mesh, const Patch& patch)
{
    std::vector<Vector3> normals;
    for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
    {
        const Vector3 a = face_area_vector(mesh, f);
        normals.push_back(a / (a.norm() + constants::vsmall));
    }
    return normals;
}

//! OpenFOAM's gAverage: the sum over the ranks over the count over the ranks.
Vector3 average_over_ranks(const std::vector<Vector3>& normals, const parallel::Communicator& comm)
{
    Vector3 sum = Vector3::Zero();
    for (const Vector3& n : normals)
        sum += n;
    const std::int64_t count = comm.sum(std::int64_t(normals.size()));
    for (int k = 0; k < 3; ++k)
        sum[k] = comm.sum(sum[k]);
    return count > 0 ? Vector3(sum / double(count)) : Vector3::Zero();
}

} // namespace

std::vector<NonPlanarSymmetryPlane> non_planar_symmetry_planes(const PolyMesh& mesh,
                                                               const parallel::Communicator& comm)
{
    std::vector<NonPlanarSymmetryPlane> found;
    for (const Patch& patch : mesh.patches)
    {
        if (patch.type != "symmetryPlane")
            continue;
        const std::vector<Vector3> normals = unit_normals(mesh, patch);
        const Vector3 average = average_over_ranks(normals, comm);
        std::int64_t off = 0;
        double worst = 0.0;
        for (const Vector3& n : normals)
        {
            const double d = (average - n).squaredNorm();
            off += d > symmetry_plane_tolerance ? 1 : 0;
            worst = std::max(worst, d);
        }
        off = comm.sum(off);
        worst = comm.max(worst);
        if (off > 0)
            found.push_back({patch.name, Index(off), worst});
    }
    return found;
}

} // namespace meshmorph
