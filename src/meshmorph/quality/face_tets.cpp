// SPDX-License-Identifier: GPL-3.0-or-later
// Face-decomposition tet quality in OpenFOAM's operation order.
#include "meshmorph/quality/face_tets.h"

#include <algorithm>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;
using detail::tet_quality;

namespace
{

//! The points of one face and the cell centres on either side (cn = co on the boundary).
struct FaceTets
{
    const Points& points;
    std::span<const Index> face;
    FoamVector cf, co, cn;
    bool internal;
    //! The base point must suit the tets on both sides: internal and coupled faces
    //! (findSharedBasePoint, with the cell centre across a coupled face).
    bool shared_base;

    FaceTets(const PolyMesh& mesh, const MeshGeometry& g, Index f,
             const CoupledFaces* coupled = nullptr)
        : points(mesh.points), face(mesh.faces[f]), cf(row(g.face_centres, f)),
          co(row(g.cell_centres, mesh.owner[f])), cn(co), internal(f < mesh.n_internal_faces()),
          shared_base(internal)
    {
        if (internal)
            cn = row(g.cell_centres, mesh.neighbour[f]);
        else if (coupled && coupled->coupled_boundary(mesh, f))
        {
            cn = row(coupled->neighbour_cell_centres, f - mesh.n_internal_faces());
            shared_base = true;
        }
    }
    FoamVector p(std::size_t i) const { return row(points, face[i]); }
    //! The point after the i-th (cyclic).
    FoamVector next(std::size_t i) const { return row(points, face[(i + 1) % face.size()]); }

    //! Whether some face point is a decomposition base whose tets all have quality > min
    //! (polyMeshTetDecomposition::findBasePoint).
    bool has_base_point(double min) const
    {
        const std::size_t n = face.size();
        for (std::size_t b = 0; b < n; ++b)
        {
            const FoamVector pb = p(b);
            double min_q = constants::vgreat;
            for (std::size_t t = 1; t + 1 < n; ++t)
            {
                const std::size_t i = (b + t) % n;
                const FoamVector pi = p(i), pj = next(i);
                double q = tet_quality(co, pb, pi, pj);
                if (shared_base)
                    q = std::min(q, tet_quality(cn, pb, pj, pi));
                min_q = std::min(min_q, q);
            }
            if (min_q > min)
                return true;
        }
        return false;
    }
};

char tet_errors(const FaceTets& t)
{
    constexpr double tol = constants::small * constants::small;
    const std::size_t n = t.face.size();
    char errors = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (tet_quality(t.p(i), t.next(i), t.cf, t.co) > -tol)
        {
            ++errors;
            break;
        }
    if (t.internal)
        for (std::size_t i = 0; i < n; ++i)
            if (tet_quality(t.p(i), t.next(i), t.cf, t.cn) < tol)
            {
                ++errors;
                break;
            }
    if (!t.has_base_point(tol))
        ++errors;
    return errors;
}

bool tet_quality_below(const FaceTets& t, double min_quality)
{
    for (std::size_t i = 0; i < t.face.size(); ++i)
    {
        const FoamVector pi = t.p(i), pj = t.next(i);
        if (tet_quality(pi, pj, t.co, t.cf) < min_quality)
            return true;
        if (t.internal && tet_quality(pi, pj, t.cf, t.cn) < min_quality)
            return true;
    }
    return !t.has_base_point(min_quality);
}

} // namespace

std::vector<char> face_tet_errors(const PolyMesh& mesh, const MeshGeometry& g)
{
    const Index n_faces = mesh.n_faces();
    std::vector<char> errors(static_cast<std::size_t>(n_faces), 0);
#pragma omp parallel for schedule(dynamic,                                                         \
                                  detail::loop_piece) if (n_faces > detail::parallel_threshold)
    for (Index f = 0; f < n_faces; ++f)
        errors[f] = tet_errors(FaceTets(mesh, g, f));
    return errors;
}

std::vector<char> faces_with_tet_quality_below(const PolyMesh& mesh, const MeshGeometry& g,
                                               double min_quality, const CoupledFaces* coupled)
{
    return detail::per_face_flags(
        mesh.n_faces(),
        [&](Index f) { return tet_quality_below(FaceTets(mesh, g, f, coupled), min_quality); });
}

} // namespace meshmorph
