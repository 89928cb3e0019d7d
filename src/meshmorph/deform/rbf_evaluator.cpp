// SPDX-License-Identifier: GPL-3.0-or-later
// Blocked RBF evaluation. The inner loop runs over a block of points for one centre so that
// GCC vectorises it without reassociating sums (-O3 -march=native, -fno-math-errno for sqrt);
// the triharmonic kernel (the default) has a loop of its own on eight-lane vectors (an
// overload of sum_block). Every point accumulates its centres in index order, so the result
// does not depend on the number of threads or on the block a point lands in.
#include "meshmorph/deform/rbf_evaluator.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/triharmonic8.h"

namespace meshmorph::detail
{
namespace
{

constexpr int point_block = 64;
constexpr std::size_t centre_pad = 8;

struct Triharmonic
{
    double operator()(double r2) const { return r2 * std::sqrt(r2); }
};
struct Biharmonic
{
    double operator()(double r2) const { return std::sqrt(r2); }
};
struct PolyharmonicOdd
{
    int half; // r^(2 half + 1)
    double operator()(double r2) const
    {
        double f = std::sqrt(r2);
        for (int k = 0; k < half; ++k)
            f *= r2;
        return f;
    }
};
struct Gaussian
{
    double eps2;
    double operator()(double r2) const { return std::exp(-eps2 * r2); }
};
struct Multiquadric
{
    double eps2;
    double operator()(double r2) const { return std::sqrt(1.0 + eps2 * r2); }
};
struct InverseMultiquadric
{
    double eps2;
    double operator()(double r2) const { return 1.0 / std::sqrt(1.0 + eps2 * r2); }
};
struct WendlandC2
{
    double inv_support;
    double operator()(double r2) const
    {
        const double t = std::sqrt(r2) * inv_support;
        const double s = std::max(1.0 - t, 0.0);
        const double s2 = s * s;
        return s2 * s2 * (4.0 * t + 1.0);
    }
};

template <class F> void with_kernel(const KernelParams& k, F&& f)
{
    switch (k.type)
    {
    case KernelType::polyharmonic:
        if (k.power == 3)
            f(Triharmonic{});
        else if (k.power == 1)
            f(Biharmonic{});
        else
            f(PolyharmonicOdd{(k.power - 1) / 2});
        return;
    case KernelType::gaussian:
        f(Gaussian{k.eps * k.eps});
        return;
    case KernelType::multiquadric:
        f(Multiquadric{k.eps * k.eps});
        return;
    case KernelType::inverse_multiquadric:
        f(InverseMultiquadric{k.eps * k.eps});
        return;
    case KernelType::wendland_c2:
        f(WendlandC2{1.0 / k.support});
        return;
    }
}

template <class Phi>
void sum_block(const Phi& phi, const RbfModel& m, const double* __restrict px,
               const double* __restrict py, const double* __restrict pz, double* __restrict ax,
               double* __restrict ay, double* __restrict az)
{
    for (int i = 0; i < point_block; ++i)
        ax[i] = ay[i] = az[i] = 0.0;
    const std::size_t nc = m.cx.size();
    const double* cx = m.cx.data();
    const double* cy = m.cy.data();
    const double* cz = m.cz.data();
    const double* wx = m.wx.data();
    const double* wy = m.wy.data();
    const double* wz = m.wz.data();
    for (std::size_t j = 0; j < nc; ++j)
    {
        const double xj = cx[j], yj = cy[j], zj = cz[j];
        const double wxj = wx[j], wyj = wy[j], wzj = wz[j];
#pragma omp simd
        for (int i = 0; i < point_block; ++i)
        {
            const double dx = px[i] - xj;
            const double dy = py[i] - yj;
            const double dz = pz[i] - zj;
            const double f = phi(dx * dx + dy * dy + dz * dz);
            ax[i] += f * wxj;
            ay[i] += f * wyj;
            az[i] += f * wzj;
        }
    }
}

//! Every sixth centre (index j with j % newton_every == newton_every - 1) takes r^3 by Newton
//! steps, the others by the square-root unit, so that both the square-root and the
//! multiply-add units stay busy (triharmonic8.h). Timed on 1752 centres and 128k points
//! (AMD EPYC, AVX-512): every eighth centre 11% less time than all by the square root,
//! every sixth 15%, every fourth 12%.
constexpr std::size_t newton_every = 6;

//! The triharmonic sums of sixteen points (two vectors of eight) over the eight centres
//! j0 .. j0 + 7, where j0 % newton_every == Phase (a template argument: the unrolled loop
//! knows which centres take the Newton steps).
struct TriharmonicSums
{
    double8 x0, y0, z0, x1, y1, z1;
    double8 sx0 = {}, sy0 = {}, sz0 = {}, sx1 = {}, sy1 = {}, sz1 = {};

    template <std::size_t Phase> void add_eight(const RbfModel& m, std::size_t j0)
    {
#pragma GCC unroll 8
        for (std::size_t u = 0; u < centre_pad; ++u)
        {
            const std::size_t j = j0 + u;
            const double xj = m.cx[j], yj = m.cy[j], zj = m.cz[j];
            const double wxj = m.wx[j], wyj = m.wy[j], wzj = m.wz[j];
            const bool newton = (Phase + u) % newton_every == newton_every - 1;
            double8 dx = x0 - xj, dy = y0 - yj, dz = z0 - zj;
            double8 r2 = dx * dx + dy * dy + dz * dz;
            double8 f = newton ? r3_by_newton(r2) : r3_by_sqrt(r2);
            sx0 += f * wxj;
            sy0 += f * wyj;
            sz0 += f * wzj;
            dx = x1 - xj, dy = y1 - yj, dz = z1 - zj;
            r2 = dx * dx + dy * dy + dz * dz;
            f = newton ? r3_by_newton(r2) : r3_by_sqrt(r2);
            sx1 += f * wxj;
            sy1 += f * wyj;
            sz1 += f * wzj;
        }
    }
};

//! sum_block for the triharmonic kernel (chosen by overload, as with_kernel picks the
//! kernel): sixteen points at a time, their sums in registers over all the centres, in index
//! order as the generic one. Which centres take the Newton steps depends on their index
//! alone, so a point's sum does not depend on the block, the thread or the rank it is
//! evaluated on.
void sum_block(const Triharmonic&, const RbfModel& m, const double* px, const double* py,
               const double* pz, double* ax, double* ay, double* az)
{
    static_assert(point_block % 16 == 0 && centre_pad == 8 && newton_every == 6);
    const std::size_t nc = m.cx.size(); // a multiple of centre_pad
    for (int v = 0; v < point_block; v += 16)
    {
        TriharmonicSums t{load8(px + v),     load8(py + v),     load8(pz + v),
                          load8(px + v + 8), load8(py + v + 8), load8(pz + v + 8)};
        // Groups of eight start at j0 % 6 = 0, 2, 4, 0, ...
        for (std::size_t j0 = 0; j0 < nc; j0 += centre_pad)
            switch (j0 % newton_every)
            {
            case 0:
                t.add_eight<0>(m, j0);
                break;
            case 2:
                t.add_eight<2>(m, j0);
                break;
            default:
                t.add_eight<4>(m, j0);
                break;
            }
        store8(ax + v, t.sx0);
        store8(ay + v, t.sy0);
        store8(az + v, t.sz0);
        store8(ax + v + 8, t.sx1);
        store8(ay + v + 8, t.sy1);
        store8(az + v + 8, t.sz1);
    }
}

double power_int(double x, int e)
{
    double r = 1.0;
    for (int k = 0; k < e; ++k)
        r *= x;
    return r;
}

} // namespace

double KernelParams::value(double r2) const
{
    double v = 0.0;
    with_kernel(*this, [&](const auto& phi) { v = phi(r2); });
    return v;
}

void KernelParams::values_in_place(double* r2, std::size_t n) const
{
    with_kernel(*this,
                [&](const auto& phi)
                {
#pragma omp simd
                    for (std::size_t i = 0; i < n; ++i)
                        r2[i] = phi(r2[i]);
                });
}

std::vector<std::array<int, 3>> monomials(int degree)
{
    std::vector<std::array<int, 3>> out;
    for (int d = 0; d <= degree; ++d)
        for (int a = d; a >= 0; --a)
            for (int b = d - a; b >= 0; --b)
                out.push_back({a, b, d - a - b});
    return out;
}

Points RbfModel::normalise(const Eigen::Ref<const Points>& x) const
{
    Points out(x.rows(), 3);
    const double inv = 1.0 / scale;
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        for (int c = 0; c < 3; ++c)
            out(i, c) = (x(i, c) - centre[c]) * inv;
    return out;
}

void RbfModel::set_centres(const Eigen::Ref<const Points>& c)
{
    num_centres = static_cast<Index>(c.rows());
    const std::size_t m = static_cast<std::size_t>(c.rows());
    const std::size_t padded = (m + centre_pad - 1) / centre_pad * centre_pad;
    for (std::vector<double>* v : {&cx, &cy, &cz, &wx, &wy, &wz})
        v->assign(padded, 0.0);
    for (std::size_t j = 0; j < padded; ++j)
    {
        const Eigen::Index src = static_cast<Eigen::Index>(std::min(j, m - 1));
        cx[j] = c(src, 0);
        cy[j] = c(src, 1);
        cz[j] = c(src, 2);
    }
    if (kernel.type == KernelType::wendland_c2)
        grid = UniformGrid(c, kernel.support);
}

void RbfModel::write(FieldWriter& out) const
{
    out.put(kernel);
    out.put_matrix(centre);
    out.put(scale);
    out.put_matrix(rotation);
    out.put_vector(exponents);
    out.put(num_centres);
    for (const std::vector<double>* v : {&cx, &cy, &cz, &wx, &wy, &wz})
        out.put_vector(*v);
    out.put_matrix(q);
}

RbfModel RbfModel::read(FieldReader& in)
{
    RbfModel m;
    m.kernel = in.get<KernelParams>();
    m.centre = in.get_matrix<Vector3>();
    m.scale = in.get<double>();
    m.rotation = in.get_matrix<Eigen::Matrix3d>();
    m.exponents = in.get_vector<std::array<int, 3>>();
    m.num_centres = in.get<Index>();
    for (std::vector<double>* v : {&m.cx, &m.cy, &m.cz, &m.wx, &m.wy, &m.wz})
        *v = in.get_vector<double>();
    m.q = in.get_matrix<Eigen::Matrix<double, Eigen::Dynamic, 3>>();
    const std::size_t padded = m.cx.size();
    bool consistent = m.num_centres >= 0 && static_cast<std::size_t>(m.num_centres) <= padded &&
                      padded % centre_pad == 0 && m.q.rows() == Eigen::Index(m.exponents.size());
    for (const std::vector<double>* v : {&m.cy, &m.cz, &m.wx, &m.wy, &m.wz})
        consistent = consistent && v->size() == padded;
    if (!consistent)
        throw IoError("fitted field: inconsistent RBF centres");
    if (m.kernel.type == KernelType::wendland_c2)
    {
        Points c(m.num_centres, 3);
        for (Index j = 0; j < m.num_centres; ++j)
            c.row(j) << m.cx[std::size_t(j)], m.cy[std::size_t(j)], m.cz[std::size_t(j)];
        m.grid = UniformGrid(c, m.kernel.support);
    }
    return m;
}

void RbfModel::set_coefficients(const Eigen::Ref<const Eigen::MatrixXd>& w,
                                const Eigen::Ref<const Eigen::MatrixXd>& coefficients)
{
    for (Eigen::Index j = 0; j < w.rows(); ++j)
    {
        wx[std::size_t(j)] = w(j, 0);
        wy[std::size_t(j)] = w(j, 1);
        wz[std::size_t(j)] = w(j, 2);
    }
    q = coefficients;
}

Eigen::MatrixXd RbfModel::polynomial_matrix(const Eigen::Ref<const Points>& x) const
{
    Eigen::MatrixXd P(x.rows(), static_cast<Eigen::Index>(exponents.size()));
    for (Eigen::Index i = 0; i < x.rows(); ++i)
    {
        const Vector3 t = rotation.transpose() * x.row(i).transpose();
        for (std::size_t k = 0; k < exponents.size(); ++k)
            P(i, Eigen::Index(k)) = power_int(t[0], exponents[k][0]) *
                                    power_int(t[1], exponents[k][1]) *
                                    power_int(t[2], exponents[k][2]);
    }
    return P;
}

Eigen::MatrixXd RbfModel::kernel_matrix(const Eigen::Ref<const Points>& x) const
{
    const Eigen::Index k = x.rows();
    const Eigen::Index m = num_centres;
    Eigen::MatrixXd K(k, m);
    const Eigen::VectorXd xs = x.col(0), ys = x.col(1), zs = x.col(2);
    with_kernel(kernel,
                [&](const auto& phi)
                {
#pragma omp parallel for schedule(static) if (k * m > 20000)
                    for (Eigen::Index j = 0; j < m; ++j)
                    {
                        const double xj = cx[std::size_t(j)], yj = cy[std::size_t(j)],
                                     zj = cz[std::size_t(j)];
                        double* col = K.col(j).data();
#pragma omp simd
                        for (Eigen::Index i = 0; i < k; ++i)
                        {
                            const double dx = xs[i] - xj, dy = ys[i] - yj, dz = zs[i] - zj;
                            col[i] = phi(dx * dx + dy * dy + dz * dz);
                        }
                    }
                });
    return K;
}

namespace
{

//! A block of points, normalised; a short last block repeats its last point (the kernels
//! run on whole blocks).
void load_block(const RbfModel& m, const Eigen::Ref<const Points>& points, Eigen::Index i0,
                int count, double* px, double* py, double* pz)
{
    const double inv = 1.0 / m.scale;
    for (int i = 0; i < point_block; ++i)
    {
        const Eigen::Index src = i0 + std::min(i, count - 1);
        px[i] = (points(src, 0) - m.centre[0]) * inv;
        py[i] = (points(src, 1) - m.centre[1]) * inv;
        pz[i] = (points(src, 2) - m.centre[2]) * inv;
    }
}

//! The kernel sum of a compactly supported kernel: only the centres within its support,
//! found in the grid.
template <class Phi>
void sum_compact_block(const Phi& phi, const RbfModel& m, int count, const double* px,
                       const double* py, const double* pz, double* ax, double* ay, double* az)
{
    const double support2 = m.kernel.support * m.kernel.support;
    for (int i = 0; i < count; ++i)
    {
        double sx = 0.0, sy = 0.0, sz = 0.0;
        m.grid.for_each_near(px[i], py[i], pz[i],
                             [&](Eigen::Index j)
                             {
                                 const std::size_t u = std::size_t(j);
                                 const double dx = px[i] - m.cx[u], dy = py[i] - m.cy[u],
                                              dz = pz[i] - m.cz[u];
                                 const double r2 = dx * dx + dy * dy + dz * dz;
                                 if (r2 < support2)
                                 {
                                     const double f = phi(r2);
                                     sx += f * m.wx[u];
                                     sy += f * m.wy[u];
                                     sz += f * m.wz[u];
                                 }
                             });
        ax[i] = sx;
        ay[i] = sy;
        az[i] = sz;
    }
}

//! Adds the polynomial part to the kernel sums and stores the block's displacements.
void store_block(const RbfModel& m, Eigen::Index i0, int count, const double* px, const double* py,
                 const double* pz, const double* ax, const double* ay, const double* az,
                 Eigen::Ref<Points> out)
{
    const Eigen::Index p = static_cast<Eigen::Index>(m.exponents.size());
    for (int i = 0; i < count; ++i)
    {
        double dx = ax[i], dy = ay[i], dz = az[i];
        if (p > 0)
        {
            const Vector3 xh(px[i], py[i], pz[i]);
            const Vector3 t = m.rotation.transpose() * xh;
            for (Eigen::Index k = 0; k < p; ++k)
            {
                const std::array<int, 3>& e = m.exponents[std::size_t(k)];
                const double v =
                    power_int(t[0], e[0]) * power_int(t[1], e[1]) * power_int(t[2], e[2]);
                dx += v * m.q(k, 0);
                dy += v * m.q(k, 1);
                dz += v * m.q(k, 2);
            }
        }
        out(i0 + i, 0) = dx;
        out(i0 + i, 1) = dy;
        out(i0 + i, 2) = dz;
    }
}

} // namespace

void RbfModel::evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const
{
    const Eigen::Index n = points.rows();
    const Eigen::Index nblocks = (n + point_block - 1) / point_block;
    const bool compact = kernel.type == KernelType::wendland_c2;
    with_kernel(kernel,
                [&](const auto& phi)
                {
#pragma omp parallel for schedule(dynamic,                                                         \
                                  8) if (n * std::max <Eigen::Index>(num_centres, 64) > 50000)
                    for (Eigen::Index b = 0; b < nblocks; ++b)
                    {
                        alignas(64) double px[point_block], py[point_block], pz[point_block];
                        alignas(64) double ax[point_block], ay[point_block], az[point_block];
                        const Eigen::Index i0 = b * point_block;
                        const int count =
                            static_cast<int>(std::min<Eigen::Index>(point_block, n - i0));
                        load_block(*this, points, i0, count, px, py, pz);
                        if (compact)
                            sum_compact_block(phi, *this, count, px, py, pz, ax, ay, az);
                        else
                            sum_block(phi, *this, px, py, pz, ax, ay, az);
                        store_block(*this, i0, count, px, py, pz, ax, ay, az, out);
                    }
                });
}

void RbfModel::transpose_sums(const Eigen::Ref<const Points>& points,
                              const Eigen::Ref<const Points>& G, Eigen::MatrixXd& KtG,
                              Eigen::MatrixXd& PtG) const
{
    // Pieces small enough for their kernel matrix (2048 x centres) to stay modest.
    constexpr Eigen::Index piece = 2048;
    const Eigen::Index n = points.rows(), pieces = (n + piece - 1) / piece;
    std::vector<Eigen::MatrixXd> kernel_part(static_cast<std::size_t>(pieces));
    std::vector<Eigen::MatrixXd> poly_part(kernel_part.size());
#pragma omp parallel for schedule(dynamic, 1) if (pieces > 1)
    for (Eigen::Index k = 0; k < pieces; ++k)
    {
        const Eigen::Index begin = k * piece, rows = std::min(piece, n - begin);
        const Points xn = normalise(points.middleRows(begin, rows));
        kernel_part[std::size_t(k)] = kernel_matrix(xn).transpose() * G.middleRows(begin, rows);
        poly_part[std::size_t(k)] = polynomial_matrix(xn).transpose() * G.middleRows(begin, rows);
    }
    KtG = Eigen::MatrixXd::Zero(num_centres, 3);
    PtG = Eigen::MatrixXd::Zero(Eigen::Index(exponents.size()), 3);
    for (Eigen::Index k = 0; k < pieces; ++k)
    {
        KtG += kernel_part[std::size_t(k)];
        PtG += poly_part[std::size_t(k)];
    }
}

} // namespace meshmorph::detail
