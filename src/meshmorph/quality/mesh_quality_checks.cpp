// SPDX-License-Identifier: GPL-3.0-or-later
// checkMesh -meshQuality: snappyHexMesh's meshQualityDict criteria (OpenFOAM's
// motionSmoother::checkMesh / polyMeshGeometry checks), docs/checkmesh-spec.md §5.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "meshmorph/quality/check_mesh.h"
#include "meshmorph/quality/foam_vector.h"

namespace meshmorph
{

using detail::FoamVector;
using detail::row;

namespace
{

constexpr double small = constants::small;
constexpr double vsmall = constants::vsmall;

//! std::setw: left-justified, or right after a polyhedra breakdown (see check_mesh.cpp).
std::string justify(const std::string& text, std::size_t width, bool right)
{
    if (text.size() >= width)
        return text;
    const std::string fill(width - text.size(), ' ');
    return right ? fill + text : text + fill;
}

FoamVector tri_area_normal(const FoamVector& a, const FoamVector& b, const FoamVector& c)
{
    return 0.5 * detail::cross(b - a, c - a);
}

} // namespace

// Called by check_mesh(). The flags of every criterion are computed per face in parallel,
// then merged in criterion order into one cumulative set, counting the faces each criterion
// newly adds -- OpenFOAM's "faces in error" lines.
void check_mesh_quality_dict(const PolyMesh& mesh, const CompactList& cell_faces,
                             const MeshGeometry& g, const MeshQualitySettings& q, int precision,
                             bool right_justify, std::ostringstream& out, QualityReport& report,
                             const std::vector<double>& skewness)
{
    const Index n_faces = mesh.n_faces();
    const Index n_int = mesh.n_internal_faces();
    const Points& pts = mesh.points;
    const auto s = [&](double v) { return format_scalar(v, precision); };
    const auto w = [&](const std::string& text, std::size_t width) {
        return justify(text, width, right_justify);
    };
    std::vector<char> in_error(static_cast<std::size_t>(n_faces), 0);
    std::vector<char> flag(static_cast<std::size_t>(n_faces), 0);
    out << "Checking faces in error :\n";

    const auto merge = [&](const std::string& key, const std::string& line) {
        Index added = 0;
        for (Index f = 0; f < n_faces; ++f)
            if (flag[f] && !in_error[f])
            {
                in_error[f] = 1;
                ++added;
            }
        out << line << added << "\n";
        report.mesh_quality_failures.emplace_back(key, added);
    };
    const auto run = [&](const std::string& key, const std::string& line, auto&& test) {
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index f = 0; f < n_faces; ++f)
            flag[f] = test(f) ? 1 : 0;
        merge(key, line);
    };
    const auto cc = [&](Index cell) { return row(g.cell_centres, cell); };
    const auto fc = [&](Index f) { return row(g.face_centres, f); };
    const auto fa = [&](Index f) { return row(g.face_areas, f); };

    if (q.max_non_ortho < 180.0 - small)
    {
        const double threshold = std::cos(detail::deg_to_rad(q.max_non_ortho));
        run("maxNonOrtho",
            "    non-orthogonality > " + w(s(q.max_non_ortho), 3) +
                " degrees                        : ",
            [&](Index f) {
                if (f >= n_int)
                    return false;
                const FoamVector d = cc(mesh.neighbour[f]) - cc(mesh.owner[f]);
                const FoamVector a = fa(f);
                return detail::dot(d, a) / (detail::mag(d) * detail::mag(a) + vsmall) < threshold;
            });
    }
    if (q.min_vol > -1e15)
    {
        run("minVol",
            "    faces with face pyramid volume < " + w(s(q.min_vol), 5) +
                "                 : ",
            [&](Index f) {
                const FoamVector cf = fc(f), af = fa(f);
                const double own = (1.0 / 3.0) * detail::dot(af, cc(mesh.owner[f]) - cf);
                if (own > -q.min_vol)
                    return true;
                if (f < n_int)
                {
                    const double nei = (1.0 / 3.0) * detail::dot(af, cc(mesh.neighbour[f]) - cf);
                    if (nei < q.min_vol)
                        return true;
                }
                return false;
            });
    }
    if (q.min_tet_quality > -1e15)
    {
        const double t = q.min_tet_quality;
        run("minTetQuality",
            "    faces with face-decomposition tet quality < " + w(s(t), 5) + "      : ",
            [&](Index f) {
                const std::span<const Index> face = mesh.faces[f];
                const std::size_t n = face.size();
                const FoamVector cf = fc(f), co = cc(mesh.owner[f]);
                const bool internal = f < n_int;
                const FoamVector cn = internal ? cc(mesh.neighbour[f]) : co;
                for (std::size_t i = 0; i < n; ++i)
                {
                    const FoamVector pi = row(pts, face[i]), pj = row(pts, face[(i + 1) % n]);
                    if (detail::tet_quality(pi, pj, co, cf) < t)
                        return true;
                    if (internal && detail::tet_quality(pi, pj, cf, cn) < t)
                        return true;
                }
                for (std::size_t b = 0; b < n; ++b)
                {
                    const FoamVector pb = row(pts, face[b]);
                    double min_q = constants::vgreat;
                    for (std::size_t k = 1; k + 1 < n; ++k)
                    {
                        const std::size_t i = (b + k) % n, j = (i + 1) % n;
                        const FoamVector pi = row(pts, face[i]), pj = row(pts, face[j]);
                        double qq = detail::tet_quality(co, pb, pi, pj);
                        if (internal)
                            qq = std::min(qq, detail::tet_quality(cn, pb, pj, pi));
                        min_q = std::min(min_q, qq);
                    }
                    if (min_q > t)
                        return false;
                }
                return true;
            });
    }
    if (q.max_concave < 180.0 - small)
    {
        const double max_sin = std::sin(detail::deg_to_rad(q.max_concave));
        run("maxConcave",
            "    faces with concavity > " + w(s(q.max_concave), 3) +
                " degrees                     : ",
            [&](Index f) {
                const std::span<const Index> face = mesh.faces[f];
                if (face.empty())
                    return false;
                FoamVector normal = fa(f);
                normal /= detail::mag(normal) + vsmall;
                FoamVector e_prev = row(pts, face.front()) - row(pts, face.back());
                double mag_prev = detail::mag(e_prev);
                e_prev /= mag_prev + vsmall;
                for (std::size_t i = 0; i < face.size(); ++i)
                {
                    FoamVector e = row(pts, face[(i + 1) % face.size()]) - row(pts, face[i]);
                    const double mag_e = detail::mag(e);
                    e /= mag_e + vsmall;
                    if (mag_prev > small && mag_e > small)
                    {
                        FoamVector n = detail::cross(e_prev, e);
                        const double mag_n = detail::mag(n);
                        if (mag_n >= max_sin)
                        {
                            n /= mag_n;
                            if (detail::dot(n, normal) < small)
                                return true;
                        }
                    }
                    e_prev = e;
                    mag_prev = mag_e;
                }
                return false;
            });
    }
    if (q.min_area > -small)
    {
        run("minArea",
            "    faces with area < " + w(s(q.min_area), 5) +
                " m^2                            : ",
            [&](Index f) { return detail::mag(fa(f)) < q.min_area; });
    }
    if (q.max_internal_skewness > 0 || q.max_boundary_skewness > 0)
    {
        run("maxInternalSkewness",
            "    faces with skewness > " + w(s(q.max_internal_skewness), 3) + " (internal) or " +
                w(s(q.max_boundary_skewness), 3) + " (boundary) : ",
            [&](Index f) {
                return skewness[f] > (f < n_int ? q.max_internal_skewness
                                                : q.max_boundary_skewness);
            });
    }
    if (q.min_face_weight >= 0 && q.min_face_weight < 1)
    {
        run("minFaceWeight",
            "    faces with interpolation weights (0..1)  < " + w(s(q.min_face_weight), 5) +
                "       : ",
            [&](Index f) {
                if (f >= n_int)
                    return false;
                const FoamVector cf = fc(f), af = fa(f);
                const double d_own = std::abs(detail::dot(af, cf - cc(mesh.owner[f])));
                const double d_nei = std::abs(detail::dot(af, cc(mesh.neighbour[f]) - cf));
                return std::min(d_nei, d_own) / (d_nei + d_own + vsmall) < q.min_face_weight;
            });
    }
    if (q.min_vol_ratio >= 0)
    {
        run("minVolRatio",
            "    faces with volume ratio of neighbour cells < " + w(s(q.min_vol_ratio), 5) +
                "     : ",
            [&](Index f) {
                if (f >= n_int)
                    return false;
                const double vo = std::abs(g.cell_volumes[mesh.owner[f]]);
                const double vn = std::abs(g.cell_volumes[mesh.neighbour[f]]);
                return std::min(vo, vn) / (std::max(vo, vn) + vsmall) < q.min_vol_ratio;
            });
    }
    if (q.min_twist > -1)
    {
        run("minTwist",
            "    faces with face twist < " + w(s(q.min_twist), 5) +
                "                          : ",
            [&](Index f) {
                const std::span<const Index> face = mesh.faces[f];
                if (face.size() <= 3)
                    return false;
                FoamVector nf = f < n_int ? cc(mesh.neighbour[f]) - cc(mesh.owner[f])
                                          : fc(f) - cc(mesh.owner[f]);
                nf /= detail::mag(nf) + vsmall;
                if (nf.x == 0 && nf.y == 0 && nf.z == 0)
                    return false;
                const FoamVector cf = fc(f);
                for (std::size_t i = 0; i < face.size(); ++i)
                {
                    const FoamVector tri = tri_area_normal(
                        row(pts, face[i]), row(pts, face[(i + 1) % face.size()]), cf);
                    const double m = detail::mag(tri);
                    if (m > vsmall && detail::dot(nf, tri / m) < q.min_twist)
                        return true;
                }
                return false;
            });
    }
    if (q.min_triangle_twist > -1)
    {
        run("minTriangleTwist",
            "    faces with triangle twist < " + w(s(q.min_triangle_twist), 5) +
                "                      : ",
            [&](Index f) {
                const std::span<const Index> face = mesh.faces[f];
                const std::size_t n = face.size();
                if (n <= 3)
                    return false;
                const FoamVector cf = fc(f);
                const auto tri = [&](std::size_t i) {
                    return tri_area_normal(row(pts, face[i]), row(pts, face[(i + 1) % n]), cf);
                };
                std::size_t start = n;
                FoamVector prev;
                for (std::size_t i = 0; i < n; ++i)
                {
                    prev = tri(i);
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
                    FoamVector t = tri(i);
                    const double m = detail::mag(t);
                    if (m > vsmall)
                    {
                        t /= m;
                        if (detail::dot(prev, t) < q.min_triangle_twist)
                            return true;
                        prev = t;
                    }
                    else if (q.min_triangle_twist > 0)
                        return true;
                } while (i != start);
                return false;
            });
    }
    if (q.min_face_flatness > -small)
    {
        run("minFaceFlatness",
            "    faces with flatness < " + w(s(q.min_face_flatness), 5) +
                "                      : ",
            [&](Index f) {
                const std::span<const Index> face = mesh.faces[f];
                if (face.size() <= 3)
                    return false;
                const FoamVector cf = fc(f);
                double sum = 0;
                for (std::size_t i = 0; i < face.size(); ++i)
                    sum += detail::mag(tri_area_normal(row(pts, face[i]),
                                                       row(pts, face[(i + 1) % face.size()]), cf));
                // OpenFOAM's ratio is sum/|Af| >= 1 (a quirk, reproduced: spec §5).
                return sum / detail::mag(fa(f)) < q.min_face_flatness;
            });
    }
    if (q.min_determinant > -1)
    {
        const Index n_cells = mesh.n_cells;
        std::vector<char> bad_cell(static_cast<std::size_t>(n_cells), 0);
#pragma omp parallel for schedule(static) if (mesh.n_faces() > detail::parallel_threshold)
        for (Index cell = 0; cell < n_cells; ++cell)
        {
            double t[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
            double mag_sum = 0;
            for (Index f : cell_faces[cell])
            {
                const FoamVector a = fa(f);
                const double m = detail::mag(a);
                mag_sum += m;
                const FoamVector u = a / (m + vsmall);
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j)
                        t[i][j] += a[i] * u[j];
            }
            for (auto& r : t)
                for (double& v : r)
                    v /= mag_sum + vsmall;
            const double det = t[0][0] * t[1][1] * t[2][2] + t[0][1] * t[1][2] * t[2][0] +
                               t[0][2] * t[1][0] * t[2][1] - t[0][0] * t[1][2] * t[2][1] -
                               t[0][1] * t[1][0] * t[2][2] - t[0][2] * t[1][1] * t[2][0];
            bad_cell[cell] = det / 0.037037037037037 < q.min_determinant;
        }
        std::fill(flag.begin(), flag.end(), 0);
        for (Index cell = 0; cell < n_cells; ++cell)
            if (bad_cell[cell])
                for (Index f : cell_faces[cell])
                    flag[f] = 1;
        merge("minDeterminant", "    faces on cells with determinant < " +
                                    w(s(q.min_determinant), 5) + "                : ");
    }
    Index total = 0;
    for (char e : in_error)
        total += e;
    report.mesh_quality_faces = total;
    std::vector<Index> faces;
    for (Index f = 0; f < n_faces; ++f)
        if (in_error[f])
            faces.push_back(f);
    if (!faces.empty())
        report.sets.push_back({"meshQualityFaces", MeshSet::Kind::face, std::move(faces)});
}

} // namespace meshmorph
