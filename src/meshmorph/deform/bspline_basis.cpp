// SPDX-License-Identifier: GPL-3.0-or-later
// Uniform cubic B-spline lattice: basis values, Greville control points, local coordinates.
#include "meshmorph/deform/bspline_basis.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>

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
    if (!box.origin.allFinite() || !box.axes.allFinite())
        throw InvalidInput("FFD lattice box is not finite");
    const double det = box.axes.determinant();
    const double scale = box.axes.colwise().norm().prod();
    if (!(std::abs(det) > 1e-12 * scale) || !(scale > 0.0))
        throw InvalidInput("FFD lattice box is degenerate (its edge vectors are linearly "
                           "dependent or zero)");
    inverse_axes_ = box.axes.inverse();
    const Eigen::Matrix3d off = box.axes - Eigen::Matrix3d(box.axes.diagonal().asDiagonal());
    axis_aligned_ = off.cwiseAbs().maxCoeff() == 0.0;
    control_.resize(size(), 3);
    for (int k = 0; k < counts[2]; ++k)
        for (int j = 0; j < counts[1]; ++j)
            for (int i = 0; i < counts[0]; ++i)
            {
                const Vector3 u(double(i - 1) / (counts[0] - 3), double(j - 1) / (counts[1] - 3),
                                double(k - 1) / (counts[2] - 3));
                control_.row(index(i, j, k)) = (box.origin + box.axes * u).transpose();
            }
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
    const Vector3 spans(counts_[0] - 3, counts_[1] - 3, counts_[2] - 3);
    Vector3 t = (inverse_axes_ * (x - box_.origin)).cwiseProduct(spans);
    if (axis_aligned_)
        return t;
    // Outside the box the spline map is not defined (the basis is clamped): keep the affine
    // coordinates, the outside policy decides.
    for (int a = 0; a < 3; ++a)
        if (!(t[a] >= 0.0 && t[a] <= spans[a]))
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
            detail::cubic_bspline(std::clamp(t[a], 0.0, spans[a]), counts_[a], first[a], w[a],
                                  dw[a]);
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
                    const Vector3 cp =
                        control_.row(index(first[0] + a, first[1] + b, first[2] + c)).transpose();
                    f += cp * (w[0][a] * w[1][b] * w[2][c]);
                    J.col(0) += cp * (dw[0][a] * w[1][b] * w[2][c]);
                    J.col(1) += cp * (w[0][a] * dw[1][b] * w[2][c]);
                    J.col(2) += cp * (w[0][a] * w[1][b] * dw[2][c]);
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
    constexpr double snap = 1e-9;
    for (int a = 0; a < 3; ++a)
    {
        const double hi = counts_[a] - 3;
        if (!(t[a] >= -snap && t[a] <= hi + snap))
        {
            if (outside == FfdOutside::zero || !std::isfinite(t[a]))
                return 0;
        }
        t[a] = std::clamp(t[a], 0.0, hi);
    }
    int first[3];
    double w[3][4];
    for (int a = 0; a < 3; ++a)
        detail::cubic_bspline(t[a], counts_[a], first[a], w[a], nullptr);
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
