// SPDX-License-Identifier: GPL-3.0-or-later
// Cyclic transforms and the cells across coupled faces, in OpenFOAM's operation order
// (cyclicPolyPatch::calcTransforms, coupledPolyPatch::calcTransformTensors, syncTools).
#include "meshmorph/mesh/coupled_patches.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;

namespace
{

constexpr double default_match_tolerance = 1e-4; // coupledPolyPatch::defaultMatchTol_

using Tensor = Eigen::Matrix3d;

FoamVector foam(const Vector3& v)
{
    return {v.x(), v.y(), v.z()};
}

Vector3 eigen(const FoamVector& v)
{
    return {v.x, v.y, v.z};
}

//! T & v, each row summed left to right (OpenFOAM's Tensor & Vector).
FoamVector apply(const Tensor& t, const FoamVector& v)
{
    return {t(0, 0) * v.x + t(0, 1) * v.y + t(0, 2) * v.z,
            t(1, 0) * v.x + t(1, 1) * v.y + t(1, 2) * v.z,
            t(2, 0) * v.x + t(2, 1) * v.y + t(2, 2) * v.z};
}

//! A & B with each entry summed left to right (OpenFOAM's Tensor & Tensor).
Tensor multiply(const Tensor& a, const Tensor& b)
{
    Tensor c;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            c(i, j) = a(i, 0) * b(0, j) + a(i, 1) * b(1, j) + a(i, 2) * b(2, j);
    return c;
}

Tensor rows(const FoamVector& x, const FoamVector& y, const FoamVector& z)
{
    Tensor t;
    t << x.x, x.y, x.z, y.x, y.y, y.z, z.x, z.y, z.z;
    return t;
}

//! Vector::normalise: zero below ROOTVSMALL.
FoamVector normalised(const FoamVector& v)
{
    const double m = detail::mag(v);
    return m < constants::rootvsmall ? FoamVector{} : v / m;
}

//! transform.H rotationTensor(n1, n2): the rotation taking unit n1 onto unit n2.
Tensor rotation_tensor(const FoamVector& n1, const FoamVector& n2)
{
    const double s = detail::dot(n1, n2);
    const FoamVector n3 = detail::cross(n1, n2);
    const double mag_sqr_n3 = detail::mag_sqr(n3);
    Tensor t = Tensor::Identity();
    if (mag_sqr_n3 > constants::small)
    {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                t(i, j) = s * (i == j ? 1.0 : 0.0) + (1 - s) * (n3[i] * n3[j]) / mag_sqr_n3 +
                          (n2[i] * n1[j] - n1[i] * n2[j]);
    }
    else if (s < 0)
    {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                t(i, j) += 2 * n1[i] * n2[j];
    }
    return t;
}

//! sqrt of the sum of squared entries (OpenFOAM's mag of a tensor).
double mag(const Tensor& t)
{
    double s = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            s += t(i, j) * t(i, j);
    return std::sqrt(s);
}

std::string word_entry(const Patch& p, std::string_view key, std::string fallback)
{
    const std::string* v = find_entry(p, key);
    return v ? *v : fallback;
}

double scalar_entry(const Patch& p, std::string_view key, double fallback)
{
    const std::string* v = find_entry(p, key);
    return v ? std::stod(*v) : fallback;
}

FoamVector vector_entry(const Patch& p, std::string_view key)
{
    const std::string* v = find_entry(p, key);
    if (!v)
        throw InvalidInput("cyclic patch " + p.name + " has no " + std::string(key));
    std::string text = *v;
    for (char& c : text)
        if (c == '(' || c == ')')
            c = ' ';
    std::istringstream in(text);
    FoamVector r;
    if (!(in >> r.x >> r.y >> r.z))
        throw InvalidInput("cyclic patch " + p.name + ": " + std::string(key) + " is not a vector");
    return r;
}

//! The unit normal of every face of patch `p` (0 where the area is below ROOTVSMALL on both
//! sides: cyclicPolyPatch then uses a dummy (1 0 0) on both).
std::vector<FoamVector> unit_normals(const Patch& p, const MeshGeometry& g)
{
    std::vector<FoamVector> n(static_cast<std::size_t>(p.n_faces));
    for (Index i = 0; i < p.n_faces; ++i)
    {
        const FoamVector a = detail::row(g.face_areas, p.start_face + i);
        const double m = detail::mag(a);
        n[static_cast<std::size_t>(i)] = m < constants::rootvsmall ? FoamVector{1, 0, 0} : a / m;
    }
    return n;
}

//! The patch's slice of the mesh's face centres (polyPatch::faceCentres, which
//! cyclicPolyPatch::calcGeometry passes to calcTransforms).
std::vector<FoamVector> patch_face_centres(const Patch& p, const MeshGeometry& g)
{
    std::vector<FoamVector> c(static_cast<std::size_t>(p.n_faces));
    for (Index i = 0; i < p.n_faces; ++i)
        c[static_cast<std::size_t>(i)] = detail::row(g.face_centres, p.start_face + i);
    return c;
}

//! findFaceMaxRadius: (c - centre) x axis of the first face furthest from the axis.
FoamVector max_radius(const std::vector<FoamVector>& centres, const FoamVector& centre,
                      const FoamVector& axis)
{
    FoamVector best;
    double best_sqr = -1;
    for (const FoamVector& c : centres)
    {
        const FoamVector n = detail::cross(c - centre, axis);
        if (detail::mag_sqr(n) > best_sqr)
        {
            best_sqr = detail::mag_sqr(n);
            best = n;
        }
    }
    return best;
}

//! `transform rotational`: the rotation about the given axis that takes the neighbour's
//! furthest face onto this side's (cyclicPolyPatch::calcTransforms).
void set_rotational(const Patch& p, const std::vector<FoamVector>& own_ctrs,
                    const std::vector<FoamVector>& nbr_ctrs, CyclicPatch& c)
{
    const FoamVector axis_raw = vector_entry(p, "rotationAxis");
    const FoamVector axis = axis_raw / detail::mag(axis_raw);
    const FoamVector centre = vector_entry(p, "rotationCentre");
    const FoamVector n0 = normalised(max_radius(own_ctrs, centre, axis));
    const FoamVector n1 = normalised(-max_radius(nbr_ctrs, centre, axis));
    const Tensor e0 = rows(axis, detail::cross(n0, axis), n0);
    const Tensor e1 = rows(axis, detail::cross(-n1, axis), -n1);
    const Tensor rev = multiply(e1.transpose(), e0);
    c.rotation = {rev.transpose()};
    c.rotational = true;
    c.rotation_centre = eigen(centre);
}

//! calcTransformTensors for an unspecified transform: a rotation if the normals are not
//! opposite within tolerance, else the separation of the face centres (none if zero).
void set_computed(const PolyMesh& mesh, const Patch& p, const Patch& nbr, const MeshGeometry& g,
                  double match_tol, bool full_match, CyclicPatch& c)
{
    const std::vector<FoamVector> cf = patch_face_centres(p, g);
    const std::vector<FoamVector> cr = patch_face_centres(nbr, g);
    const std::vector<FoamVector> nf = unit_normals(p, g);
    const std::vector<FoamVector> nr = unit_normals(nbr, g);
    const std::vector<double> tol = face_tolerances(mesh, g, p);
    const std::size_t n = cf.size();
    const double error = match_tol * std::sqrt(1.0 * static_cast<double>(n));
    double sum_dot = 0;
    for (std::size_t i = 0; i < n; ++i)
        sum_dot += std::abs(detail::dot(nf[i], nr[i]));
    if (!full_match && sum_dot < static_cast<double>(n) - error)
    {
        for (std::size_t i = 0; i < n; ++i)
            c.rotation.push_back(rotation_tensor(-nr[i], nf[i]));
        double spread = 0;
        for (const Tensor& t : c.rotation)
            spread += mag(Tensor(t - c.rotation[0]));
        if (spread < error)
            c.rotation.resize(1);
        return;
    }
    std::vector<FoamVector> sep(n);
    bool same = true;
    for (std::size_t i = 0; i < n; ++i)
    {
        sep[i] = cr[i] - cf[i];
        const double small_sqr = (match_tol * tol[i]) * (match_tol * tol[i]);
        same = same && detail::mag_sqr(sep[i] - sep[0]) <= small_sqr;
    }
    const double small_sqr0 = (match_tol * tol[0]) * (match_tol * tol[0]);
    if (same && detail::mag_sqr(sep[0]) < small_sqr0)
        return; // collocated: no transform
    if (same)
        sep.resize(1);
    for (const FoamVector& s : sep)
        c.separation.push_back(eigen(s));
}

CyclicPatch cyclic_patch(const PolyMesh& mesh, const MeshGeometry& g, Index index)
{
    const Patch& p = mesh.patches[static_cast<std::size_t>(index)];
    CyclicPatch c;
    c.patch = index;
    c.neighbour = cyclic_neighbour_patch(mesh, index);
    const Patch& nbr = mesh.patches[static_cast<std::size_t>(c.neighbour)];
    if (nbr.n_faces != p.n_faces)
        throw InvalidInput("cyclic patch " + p.name + " has " + std::to_string(p.n_faces) +
                           " faces, its neighbour " + nbr.name + " " + std::to_string(nbr.n_faces));
    const std::string transform = word_entry(p, "transform", "unknown");
    if (transform != word_entry(nbr, "transform", "unknown"))
        throw InvalidInput("cyclic patches " + p.name + " and " + nbr.name +
                           " have different transforms");
    if (transform == "rotational")
        set_rotational(p, patch_face_centres(p, g), patch_face_centres(nbr, g), c);
    else if (transform == "translational")
        c.separation = {eigen(vector_entry(p, "separationVector"))};
    else
        set_computed(mesh, p, nbr, g, scalar_entry(p, "matchTolerance", default_match_tolerance),
                     transform == "coincidentFullMatch", c);
    return c;
}

} // namespace

Index cyclic_neighbour_patch(const PolyMesh& mesh, Index patch)
{
    const Patch& p = mesh.patches[static_cast<std::size_t>(patch)];
    const std::string name = word_entry(p, "neighbourPatch", "");
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        if (mesh.patches[i].name == name && is_coupled_patch(mesh.patches[i]))
            return static_cast<Index>(i);
    throw InvalidInput("cyclic patch " + p.name + " has no cyclic neighbourPatch '" + name + "'");
}

std::vector<double> face_tolerances(const PolyMesh& mesh, const MeshGeometry& g, const Patch& p)
{
    std::vector<double> tols(static_cast<std::size_t>(p.n_faces));
    for (Index i = 0; i < p.n_faces; ++i)
    {
        const Index f = p.start_face + i;
        const FoamVector cc = detail::row(g.face_centres, f);
        double max_len_sqr = -constants::great, max_cmpt = -constants::great;
        for (Index v : mesh.faces[f])
        {
            const FoamVector pt = detail::row(mesh.points, v);
            max_len_sqr = std::max(max_len_sqr, detail::mag_sqr(pt - cc));
            const FoamVector m = detail::cmpt_mag(pt);
            max_cmpt = std::max(max_cmpt, std::max(m.x, std::max(m.y, m.z)));
        }
        tols[static_cast<std::size_t>(i)] = std::max(
            constants::small, std::max(constants::small * max_cmpt, std::sqrt(max_len_sqr)));
    }
    return tols;
}

std::vector<char> CoupledFaces::statistics_faces() const
{
    std::vector<char> summed(internal_or_coupled.size());
    for (std::size_t f = 0; f < summed.size(); ++f)
        summed[f] = internal_or_coupled[f] && master[f];
    return summed;
}

Vector3 CyclicPatch::transform_position(const Vector3& p, Index i) const
{
    FoamVector l = foam(p);
    if (!rotation.empty())
    {
        const Tensor& t = rotation[rotation.size() == 1 ? 0 : static_cast<std::size_t>(i)];
        l = rotational ? apply(t, l - foam(rotation_centre)) + foam(rotation_centre) : apply(t, l);
    }
    else if (!separation.empty())
    {
        // Calculated on the sending side, so subtracted on the receiving one.
        l -= foam(separation[separation.size() == 1 ? 0 : static_cast<std::size_t>(i)]);
    }
    return eigen(l);
}

std::vector<CyclicPatch> cyclic_patches(const PolyMesh& mesh, const MeshGeometry& g)
{
    std::vector<CyclicPatch> cyclics;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        if (is_coupled_patch(mesh.patches[i]) && mesh.patches[i].n_faces > 0)
            cyclics.push_back(cyclic_patch(mesh, g, static_cast<Index>(i)));
    return cyclics;
}

namespace
{

void add_processor_faces(const PolyMesh& mesh, const ProcessorFaces& processors, CoupledFaces& c)
{
    const Index n_int = mesh.n_internal_faces();
    for (std::size_t b = 0; b < processors.on_processor_patch.size(); ++b)
        if (processors.on_processor_patch[b])
        {
            const std::size_t f = static_cast<std::size_t>(n_int) + b;
            c.internal_or_coupled[f] = 1;
            c.master[f] = processors.owner_side[b];
            c.neighbour_cell_centres.row(static_cast<Index>(b)) =
                processors.neighbour_cell_centres.row(static_cast<Index>(b));
            c.neighbour_cell_volumes[static_cast<Index>(b)] =
                processors.neighbour_cell_volumes[static_cast<Index>(b)];
        }
}

} // namespace

CoupledFaces coupled_faces(const PolyMesh& mesh, const MeshGeometry& g,
                           const std::vector<CyclicPatch>& cyclics,
                           const ProcessorFaces* processors)
{
    const Index n_int = mesh.n_internal_faces();
    const Index n_boundary = mesh.n_faces() - n_int;
    CoupledFaces c;
    c.internal_or_coupled.assign(static_cast<std::size_t>(mesh.n_faces()), 0);
    std::fill_n(c.internal_or_coupled.begin(), n_int, 1);
    c.master.assign(static_cast<std::size_t>(mesh.n_faces()), 1);
    // Uncoupled faces keep their own cell's values (swapBoundaryCellPositions starts there).
    c.neighbour_cell_centres.resize(n_boundary, 3);
    c.neighbour_cell_volumes.resize(n_boundary);
    for (Index b = 0; b < n_boundary; ++b)
    {
        const Index cell = mesh.owner[static_cast<std::size_t>(n_int + b)];
        c.neighbour_cell_centres.row(b) = g.cell_centres.row(cell);
        c.neighbour_cell_volumes[b] = g.cell_volumes[cell];
    }
    for (const CyclicPatch& cp : cyclics)
    {
        const Patch& p = mesh.patches[static_cast<std::size_t>(cp.patch)];
        const Patch& nbr = mesh.patches[static_cast<std::size_t>(cp.neighbour)];
        for (Index i = 0; i < p.n_faces; ++i)
        {
            const Index f = p.start_face + i;
            const Index across = mesh.owner[static_cast<std::size_t>(nbr.start_face + i)];
            c.internal_or_coupled[static_cast<std::size_t>(f)] = 1;
            c.master[static_cast<std::size_t>(f)] = cp.owner();
            const Vector3 cc = g.cell_centres.row(across).transpose();
            c.neighbour_cell_centres.row(f - n_int) = cp.transform_position(cc, i).transpose();
            c.neighbour_cell_volumes[f - n_int] = g.cell_volumes[across];
        }
    }
    if (processors)
        add_processor_faces(mesh, *processors, c);
    return c;
}

} // namespace meshmorph
