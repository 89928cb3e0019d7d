// SPDX-License-Identifier: GPL-3.0-or-later
// Face twist in OpenFOAM's operation order.
#include "meshmorph/quality/face_twist.h"

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

constexpr double vsmall = constants::vsmall;

//! The triangles (p[i], p[i+1], face centre) fanned from a face centre.
struct FaceFan
{
    const Points& points;
    std::span<const Index> face;
    FoamVector centre;

    FaceFan(const PolyMesh& mesh, const MeshGeometry& g, Index f)
        : points(mesh.points), face(mesh.faces[f]), centre(row(g.face_centres, f))
    {
    }
    //! Area vector of the i-th triangle, i in [0, size()).
    FoamVector triangle(std::size_t i) const
    {
        return detail::tri_area_normal(row(points, face[i]),
                                       row(points, face[(i + 1) % face.size()]), centre);
    }
    std::size_t size() const { return face.size(); }
};

//! The centre the twist is measured towards: the neighbour cell's, across a coupled face the
//! cell's on the other side, on other boundary faces the face's.
FoamVector across(const PolyMesh& mesh, const MeshGeometry& g, const CoupledFaces* coupled, Index f)
{
    if (f < mesh.n_internal_faces())
        return row(g.cell_centres, mesh.neighbour[f]);
    if (coupled && coupled->coupled_boundary(mesh, f))
        return row(coupled->neighbour_cell_centres, f - mesh.n_internal_faces());
    return row(g.face_centres, f);
}

bool twist_below(const PolyMesh& mesh, const MeshGeometry& g, const CoupledFaces* coupled, Index f,
                 double min_twist)
{
    const FaceFan fan(mesh, g, f);
    if (fan.size() <= 3)
        return false;
    const FoamVector own = row(g.cell_centres, mesh.owner[f]);
    FoamVector nf = across(mesh, g, coupled, f) - own;
    nf /= detail::mag(nf) + vsmall;
    if (nf.x == 0 && nf.y == 0 && nf.z == 0)
        return false;
    for (std::size_t i = 0; i < fan.size(); ++i)
    {
        const FoamVector tri = fan.triangle(i);
        const double m = detail::mag(tri);
        if (m > vsmall && detail::dot(nf, tri / m) < min_twist)
            return true;
    }
    return false;
}

bool triangle_twist_below(const PolyMesh& mesh, const MeshGeometry& g, Index f, double min_twist)
{
    const FaceFan fan(mesh, g, f);
    const std::size_t n = fan.size();
    if (n <= 3)
        return false;
    std::size_t start = n;
    FoamVector prev;
    for (std::size_t i = 0; i < n; ++i)
    {
        prev = fan.triangle(i);
        const double m = detail::mag(prev);
        if (m > vsmall)
        {
            start = i;
            prev /= m;
            break;
        }
    }
    if (start == n)
        return false;
    std::size_t i = start;
    do
    {
        i = (i + 1) % n;
        FoamVector t = fan.triangle(i);
        const double m = detail::mag(t);
        if (m > vsmall)
        {
            t /= m;
            if (detail::dot(prev, t) < min_twist)
                return true;
            prev = t;
        }
        else if (min_twist > 0)
            return true;
    } while (i != start);
    return false;
}

} // namespace

std::vector<char> faces_with_twist_below(const PolyMesh& mesh, const MeshGeometry& g,
                                         double min_twist, const CoupledFaces* coupled)
{
    return detail::per_face_flags(mesh.n_faces(), [&](Index f)
                                  { return twist_below(mesh, g, coupled, f, min_twist); });
}

std::vector<char> faces_with_triangle_twist_below(const PolyMesh& mesh, const MeshGeometry& g,
                                                  double min_twist)
{
    return detail::per_face_flags(mesh.n_faces(), [&](Index f)
                                  { return triangle_twist_below(mesh, g, f, min_twist); });
}

} // namespace meshmorph
