// SPDX-License-Identifier: GPL-3.0-or-later
// Pyramid and cell volumes along x + t dx as cubics in t, and their first root.
#include "meshmorph/quality/inversion_step.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "meshmorph/core/cubic_first_root.h"
#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

namespace
{

//! A point moving linearly: at + t * rate.
struct MovingPoint
{
    Vector3 at = Vector3::Zero();
    Vector3 rate = Vector3::Zero();
};

//! A vector quadratic in t: v0 + t v1 + t^2 v2.
struct QuadraticVector
{
    Vector3 v0 = Vector3::Zero(), v1 = Vector3::Zero(), v2 = Vector3::Zero();
};

MovingPoint moving_point(const PolyMesh& mesh, const Points& dx, Index p)
{
    return {mesh.points.row(p).transpose(), dx.row(p).transpose()};
}

//! Face f's centre: checkMesh's at t = 0, moving with the average of its points' rates.
MovingPoint face_centre(const PolyMesh& mesh, const MeshGeometry& g, const Points& dx, Index f)
{
    Vector3 rate = Vector3::Zero();
    const auto face = mesh.faces[f];
    for (Index p : face)
        rate += dx.row(p).transpose();
    return {g.face_centres.row(f).transpose(), rate / double(face.size())};
}

//! Cell c's centre: checkMesh's at t = 0, moving with the average of its faces' rates.
MovingPoint cell_centre(const MeshGeometry& g, Index c, const std::vector<MovingPoint>& faces)
{
    Vector3 rate = Vector3::Zero();
    for (const MovingPoint& f : faces)
        rate += f.rate;
    return {g.cell_centres.row(c).transpose(),
            rate / double(std::max<std::size_t>(faces.size(), 1))};
}

//! Twice face f's area vector: the sum over its edges (a, b) of (a - centre) x (b - centre),
//! quadratic in t. The sum does not depend on `centre` (the loop is closed), so it is
//! checkMesh's; a point near the face keeps the products small (no cancellation).
QuadraticVector twice_area_vector(const PolyMesh& mesh, const Points& dx, Index f,
                                  const MovingPoint& centre)
{
    QuadraticVector s;
    const auto face = mesh.faces[f];
    for (std::size_t i = 0; i < face.size(); ++i)
    {
        const MovingPoint a = moving_point(mesh, dx, face[i]);
        const MovingPoint b = moving_point(mesh, dx, face[(i + 1) % face.size()]);
        const Vector3 a0 = a.at - centre.at, a1 = a.rate - centre.rate;
        const Vector3 b0 = b.at - centre.at, b1 = b.rate - centre.rate;
        s.v0 += a0.cross(b0);
        s.v1 += a0.cross(b1) + a1.cross(b0);
        s.v2 += a1.cross(b1);
    }
    return s;
}

//! (sign / 6) w . s for w linear and s quadratic in t: a pyramid's volume as a cubic.
Cubic pyramid_volume(const MovingPoint& w, const QuadraticVector& s, double sign)
{
    const double k = sign / 6.0;
    return {k * w.at.dot(s.v0), k * (w.at.dot(s.v1) + w.rate.dot(s.v0)),
            k * (w.at.dot(s.v2) + w.rate.dot(s.v1)), k * w.rate.dot(s.v2)};
}

//! A cell's scales: its largest point distance from its centre and its largest point rate.
struct CellScales
{
    double size = 0.0, rate = 0.0;
};

CellScales cell_scales(const PolyMesh& mesh, const Points& dx, std::span<const Index> faces,
                       const MovingPoint& centre)
{
    CellScales s;
    for (Index f : faces)
        for (Index p : mesh.faces[f])
        {
            s.size = std::max(s.size, (mesh.points.row(p).transpose() - centre.at).norm());
            s.rate = std::max(s.rate, dx.row(p).norm());
        }
    return s;
}

//! Zero the coefficients of t^k that are round-off: below 1e-12 size^(3-k) rate^k, the
//! size of the products they are sums of. Otherwise a cubic that is exactly quadratic (a
//! linearised rotation's volumes, 1 + t^2 |w|^2) gets a leading coefficient of 1e-17 and
//! a root at t = 1e15 that no motion means.
Cubic without_round_off(Cubic c, const CellScales& s)
{
    double scale = s.size * s.size * s.size;
    for (std::size_t k = 1; k < 4; ++k)
    {
        scale *= s.size > 0.0 ? s.rate / s.size : 0.0;
        if (std::abs(c[k]) < 1e-12 * scale)
            c[k] = 0.0;
    }
    return c;
}

//! The first step in (0, limit] at which cell c or one of its face pyramids, positive at
//! t = 0, reaches zero volume.
double cell_inversion_step(const PolyMesh& mesh, const CompactList& cell_faces,
                           const MeshGeometry& g, const Points& dx, Index c, double limit)
{
    const std::span<const Index> faces = cell_faces[c];
    thread_local std::vector<MovingPoint> centres; // each face's, computed once per cell
    centres.clear();
    for (Index f : faces)
        centres.push_back(face_centre(mesh, g, dx, f));
    const MovingPoint centre = cell_centre(g, c, centres);
    const CellScales scales = cell_scales(mesh, dx, faces, centre);
    double first = std::numeric_limits<double>::infinity();
    Cubic volume{0.0, 0.0, 0.0, 0.0};
    for (std::size_t k = 0; k < faces.size(); ++k)
    {
        const Index f = faces[k];
        const MovingPoint& fa = centres[k];
        const MovingPoint w{fa.at - centre.at, fa.rate - centre.rate};
        const Cubic pyramid = without_round_off(
            pyramid_volume(w, twice_area_vector(mesh, dx, f, fa), mesh.owner[f] == c ? 1.0 : -1.0),
            scales);
        for (std::size_t i = 0; i < 4; ++i)
            volume[i] += pyramid[i];
        if (pyramid[0] > 0.0)
            first = std::min(first, first_nonpositive_step(pyramid, std::min(first, limit)));
    }
    volume = without_round_off(volume, scales);
    if (volume[0] > 0.0)
        first = std::min(first, first_nonpositive_step(volume, std::min(first, limit)));
    return first;
}

} // namespace

std::vector<double> cell_inversion_steps(const PolyMesh& mesh, const CompactList& cell_faces,
                                         const MeshGeometry& geometry, const Points& dx,
                                         double limit, const std::vector<Index>* cells)
{
    const Index n = cells != nullptr ? Index(cells->size()) : cell_faces.size();
    std::vector<double> steps(std::size_t(n), std::numeric_limits<double>::infinity());
#pragma omp parallel for schedule(dynamic, detail::loop_piece) if (n > detail::parallel_threshold)
    for (Index k = 0; k < n; ++k)
        steps[std::size_t(k)] = cell_inversion_step(
            mesh, cell_faces, geometry, dx, cells != nullptr ? (*cells)[std::size_t(k)] : k, limit);
    return steps;
}

double first_inversion_step(const PolyMesh& mesh, const CompactList& cell_faces,
                            const MeshGeometry& geometry, const Points& dx, double limit)
{
    const std::vector<double> steps =
        cell_inversion_steps(mesh, cell_faces, geometry, dx, limit, nullptr);
    return steps.empty() ? std::numeric_limits<double>::infinity()
                         : *std::min_element(steps.begin(), steps.end());
}

} // namespace meshmorph
