// SPDX-License-Identifier: GPL-3.0-or-later
// Cubic B-spline lattice (uniform fast path, non-uniform Cox-de Boor): basis values, Greville
// control points, local coordinates, knot insertion.
#include "meshmorph/deform/bspline_basis.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

#include "meshmorph/core/exceptions.h"

namespace meshmorph
{

FfdOutside ffd_outside_from_string(const std::string& name)
{
    if (name == "zero")
        return FfdOutside::zero;
    if (name == "clamp")
        return FfdOutside::clamp;
    throw InvalidInput("unknown FFD outside policy '" + name + "' (expected zero or clamp)");
}

std::string to_string(FfdOutside outside)
{
    return outside == FfdOutside::zero ? "zero" : "clamp";
}

namespace detail
{
void cubic_bspline(double t, int n, int& first, double* w, double* dw)
{
    const int spans = n - 3;
    int k = static_cast<int>(std::floor(t));
    k = std::clamp(k, 0, spans - 1);
    const double s = t - k;
    const double s2 = s * s, s3 = s2 * s, r = 1.0 - s;
    w[0] = r * r * r / 6.0;
    w[1] = (3.0 * s3 - 6.0 * s2 + 4.0) / 6.0;
    w[2] = (-3.0 * s3 + 3.0 * s2 + 3.0 * s + 1.0) / 6.0;
    w[3] = s3 / 6.0;
    if (dw)
    {
        dw[0] = -0.5 * r * r;
        dw[1] = 1.5 * s2 - 2.0 * s;
        dw[2] = -1.5 * s2 + s + 0.5;
        dw[3] = 0.5 * s2;
    }
    first = k;
}

void cubic_bspline(double t, const std::vector<double>& U, int& first, double* w, double* dw)
{
    const int n = static_cast<int>(U.size()) - 4;
    t = std::clamp(t, U[3], U[std::size_t(n)]);
    // Span k with U[k] <= t < U[k+1], k in [3, n-1] (t = U[n] belongs to the last span).
    int k = static_cast<int>(std::upper_bound(U.begin() + 3, U.begin() + n, t) - U.begin()) - 1;
    k = std::clamp(k, 3, n - 1);
    double left[4], right[4], N[4], N2[3] = {0.0, 0.0, 0.0};
    N[0] = 1.0;
    for (int j = 1; j <= 3; ++j)
    {
        left[j] = t - U[std::size_t(k + 1 - j)];
        right[j] = U[std::size_t(k + j)] - t;
        double saved = 0.0;
        for (int r = 0; r < j; ++r)
        {
            const double temp = N[r] / (right[r + 1] + left[j - r]);
            N[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        N[j] = saved;
        if (j == 2)
            for (int r = 0; r < 3; ++r)
                N2[r] = N[r];
    }
    for (int r = 0; r < 4; ++r)
        w[r] = N[r];
    if (dw)
    {
        // N'_{i,3} = 3 (N_{i,2} / (U_{i+3} - U_i) - N_{i+1,2} / (U_{i+4} - U_{i+1})), i = k-3+r;
        // on this span N_{k-3,2} = N_{k+1,2} = 0.
        for (int r = 0; r < 4; ++r)
        {
            const std::size_t i = std::size_t(k - 3 + r);
            const double a = r >= 1 ? N2[r - 1] / (U[i + 3] - U[i]) : 0.0;
            const double b = r <= 2 ? N2[r] / (U[i + 4] - U[i + 1]) : 0.0;
            dw[r] = 3.0 * (a - b);
        }
    }
    first = k - 3;
}
} // namespace detail

namespace
{
void check_counts(const std::array<int, 3>& counts)
{
    for (int a = 0; a < 3; ++a)
        if (counts[a] < 4)
        {
            std::ostringstream s;
            s << "FFD lattice needs at least 4 control points per axis (cubic B-splines); got "
              << counts[0] << " x " << counts[1] << " x " << counts[2];
            throw InvalidInput(s.str());
        }
}
} // namespace

FfdLattice::FfdLattice(const FfdBox& box, const std::array<int, 3>& counts)
    : box_(box), counts_(counts)
{
    check_counts(counts);
    for (int a = 0; a < 3; ++a)
    {
        std::vector<double>& U = knots_[std::size_t(a)];
        U.resize(std::size_t(counts[std::size_t(a)] + 4));
        for (std::size_t j = 0; j < U.size(); ++j)
            U[j] = double(j) - 3.0;
    }
    initialise();
}

FfdLattice::FfdLattice(const FfdBox& box, const std::array<std::vector<double>, 3>& knots)
    : box_(box), knots_(knots)
{
    for (int a = 0; a < 3; ++a)
    {
        const std::vector<double>& U = knots_[std::size_t(a)];
        if (U.size() < 8)
            throw InvalidInput("FFD lattice: axis " + std::to_string(a) + " has " +
                               std::to_string(U.size()) +
                               " knots; a cubic B-spline lattice needs at least 8 (4 control "
                               "points)");
        for (std::size_t j = 0; j < U.size(); ++j)
            if (!std::isfinite(U[j]) || (j > 0 && !(U[j] > U[j - 1])))
                throw InvalidInput("FFD lattice: the knots of axis " + std::to_string(a) +
                                   " must be finite and strictly increasing (knot " +
                                   std::to_string(j) + ")");
        counts_[std::size_t(a)] = static_cast<int>(U.size()) - 4;
    }
    initialise();
}

void FfdLattice::initialise()
{
    if (!box_.origin.allFinite() || !box_.axes.allFinite())
        throw InvalidInput("FFD lattice box is not finite");
    const double det = box_.axes.determinant();
    const double scale = box_.axes.colwise().norm().prod();
    if (!(std::abs(det) > 1e-12 * scale) || !(scale > 0.0))
        throw InvalidInput("FFD lattice box is degenerate (its edge vectors are linearly "
                           "dependent or zero)");
    inverse_axes_ = box_.axes.inverse();
    const Eigen::Matrix3d off = box_.axes - Eigen::Matrix3d(box_.axes.diagonal().asDiagonal());
    axis_aligned_ = off.cwiseAbs().maxCoeff() == 0.0;
    for (int a = 0; a < 3; ++a)
    {
        const std::vector<double>& U = knots_[std::size_t(a)];
        const int n = counts_[std::size_t(a)];
        bool uniform = true;
        for (std::size_t j = 0; j < U.size(); ++j)
            uniform = uniform && U[j] == double(j) - 3.0;
        uniform_[std::size_t(a)] = uniform;
        lo_[a] = U[3];
        hi_[a] = U[std::size_t(n)];
    }
    // Greville abscissae per axis, as box fractions. The uniform formula is kept verbatim so
    // uniform lattices are bit-identical to the original construction.
    std::array<std::vector<double>, 3> g;
    for (int a = 0; a < 3; ++a)
    {
        const std::vector<double>& U = knots_[std::size_t(a)];
        const int n = counts_[std::size_t(a)];
        g[std::size_t(a)].resize(std::size_t(n));
        for (int i = 0; i < n; ++i)
        {
            const std::size_t ui = std::size_t(i);
            g[std::size_t(a)][ui] =
                uniform_[std::size_t(a)]
                    ? double(i - 1) / (n - 3)
                    : ((U[ui + 1] + U[ui + 2] + U[ui + 3]) / 3.0 - lo_[a]) / (hi_[a] - lo_[a]);
        }
    }
    control_.resize(size(), 3);
    for (int k = 0; k < counts_[2]; ++k)
        for (int j = 0; j < counts_[1]; ++j)
            for (int i = 0; i < counts_[0]; ++i)
            {
                const Vector3 u(g[0][std::size_t(i)], g[1][std::size_t(j)], g[2][std::size_t(k)]);
                control_.row(index(i, j, k)) = (box_.origin + box_.axes * u).transpose();
            }
}

void FfdLattice::axis_basis(int a, double t, int& first, double* w, double* dw) const
{
    if (uniform_[std::size_t(a)])
        detail::cubic_bspline(t, counts_[std::size_t(a)], first, w, dw);
    else
        detail::cubic_bspline(t, knots_[std::size_t(a)], first, w, dw);
}

std::pair<double, double> FfdLattice::knot_span(int a, double t) const
{
    const std::vector<double>& U = knots_[std::size_t(a)];
    const int n = counts_[std::size_t(a)];
    t = std::clamp(t, U[3], U[std::size_t(n)]);
    int k = static_cast<int>(std::upper_bound(U.begin() + 3, U.begin() + n, t) - U.begin()) - 1;
    k = std::clamp(k, 3, n - 1);
    return {U[std::size_t(k)], U[std::size_t(k + 1)]};
}

FfdLattice FfdLattice::with_inserted_knot(int a, double t) const
{
    if (a < 0 || a > 2)
        throw InvalidInput("FFD knot insertion: axis " + std::to_string(a) + " is not 0, 1 or 2");
    if (!std::isfinite(t) || !(t > lo_[a] && t < hi_[a]))
        throw InvalidInput("FFD knot insertion: parameter outside the lattice domain");
    const std::pair<double, double> span = knot_span(a, t);
    // Knots closer than 1e-9 of the span would make a nearly repeated knot (ill-conditioned
    // basis, dividing by ~0 in Cox-de Boor).
    const double gap = 1e-9 * (span.second - span.first);
    if (!(t - span.first > gap && span.second - t > gap))
        throw InvalidInput("FFD knot insertion: parameter coincides with an existing knot");
    std::array<std::vector<double>, 3> knots = knots_;
    std::vector<double>& U = knots[std::size_t(a)];
    U.insert(std::upper_bound(U.begin(), U.end(), t), t);
    return FfdLattice(box_, knots);
}

FfdLattice FfdLattice::bounding(const Eigen::Ref<const Points>& points,
                                const std::array<int, 3>& counts, double margin)
{
    check_counts(counts);
    if (points.rows() == 0)
        throw InvalidInput("FFD lattice: no points to bound");
    if (!points.allFinite())
        throw InvalidInput("FFD lattice: points are not finite");
    if (!(margin >= 0.0))
        throw InvalidInput("FFD lattice margin must be >= 0");
    const Vector3 lo = points.colwise().minCoeff().transpose();
    const Vector3 hi = points.colwise().maxCoeff().transpose();
    Vector3 ext = hi - lo;
    double big = ext.maxCoeff();
    if (!(big > 0.0))
        big = 1.0;
    for (int a = 0; a < 3; ++a)
        if (!(ext[a] > 0.0))
            ext[a] = 1e-3 * big;
    FfdBox box;
    const Vector3 centre = 0.5 * (lo + hi);
    const Vector3 half = 0.5 * ext * (1.0 + 2.0 * margin);
    box.origin = centre - half;
    box.axes = (2.0 * half).asDiagonal();
    return FfdLattice(box, counts);
}

Vector3 FfdLattice::local_coordinates(const Vector3& x) const
{
    const Vector3 spans = hi_ - lo_;
    Vector3 t = (inverse_axes_ * (x - box_.origin)).cwiseProduct(spans) + lo_;
    if (axis_aligned_)
        return t;
    // Outside the box the spline map is not defined (the basis is clamped): keep the affine
    // coordinates, the outside policy decides.
    for (int a = 0; a < 3; ++a)
        if (!(t[a] >= lo_[a] && t[a] <= hi_[a]))
            return t;
    // Newton on x(t) = sum c_p N_p(t); exact after one step for an undeformed lattice, kept
    // general so that a pre-deformed lattice works too.
    const double tolerance = 1e-13 * box_.axes.cwiseAbs().maxCoeff();
    for (int it = 0; it < 20; ++it)
    {
        Vector3 f = -x;
        Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
        int first[3];
        double w[3][4], dw[3][4];
        for (int a = 0; a < 3; ++a)
            axis_basis(a, std::clamp(t[a], lo_[a], hi_[a]), first[a], w[a], dw[a]);
        // Residual first: the usual case (undeformed lattice) stops here without a Jacobian.
        const double* cp = control_.data();
        for (int c = 0; c < 4; ++c)
            for (int b = 0; b < 4; ++b)
            {
                const double wbc = w[1][b] * w[2][c];
                const double* row =
                    cp + 3 * std::ptrdiff_t(index(first[0], first[1] + b, first[2] + c));
                for (int a = 0; a < 4; ++a)
                {
                    const double wa = w[0][a] * wbc;
                    f[0] += wa * row[3 * a];
                    f[1] += wa * row[3 * a + 1];
                    f[2] += wa * row[3 * a + 2];
                }
            }
        if (f.cwiseAbs().maxCoeff() <= tolerance)
            break;
        f = -x;
        for (int c = 0; c < 4; ++c)
            for (int b = 0; b < 4; ++b)
                for (int a = 0; a < 4; ++a)
                {
                    const Vector3 point =
                        control_.row(index(first[0] + a, first[1] + b, first[2] + c)).transpose();
                    f += point * (w[0][a] * w[1][b] * w[2][c]);
                    J.col(0) += point * (dw[0][a] * w[1][b] * w[2][c]);
                    J.col(1) += point * (w[0][a] * dw[1][b] * w[2][c]);
                    J.col(2) += point * (w[0][a] * w[1][b] * dw[2][c]);
                }
        const Vector3 step = J.partialPivLu().solve(f);
        t -= step;
        if (step.cwiseAbs().maxCoeff() < 1e-13 * (1.0 + t.cwiseAbs().maxCoeff()))
            break;
    }
    return t;
}

int FfdLattice::basis(const Vector3& x, FfdOutside outside, Index* index_out, double* weight) const
{
    Vector3 t = local_coordinates(x);
    for (int a = 0; a < 3; ++a)
    {
        // 1e-9 mean knot spans (exactly 1e-9 for a uniform lattice).
        const double snap = 1e-9 * (hi_[a] - lo_[a]) / (counts_[a] - 3);
        if (!(t[a] >= lo_[a] - snap && t[a] <= hi_[a] + snap))
        {
            if (outside == FfdOutside::zero || !std::isfinite(t[a]))
                return 0;
        }
        t[a] = std::clamp(t[a], lo_[a], hi_[a]);
    }
    int first[3];
    double w[3][4];
    for (int a = 0; a < 3; ++a)
        axis_basis(a, t[a], first[a], w[a], nullptr);
    int n = 0;
    for (int c = 0; c < 4; ++c)
        for (int b = 0; b < 4; ++b)
            for (int a = 0; a < 4; ++a)
            {
                index_out[n] = index(first[0] + a, first[1] + b, first[2] + c);
                weight[n] = w[0][a] * w[1][b] * w[2][c];
                ++n;
            }
    return n;
}

} // namespace meshmorph
