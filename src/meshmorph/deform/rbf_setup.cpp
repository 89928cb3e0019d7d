// SPDX-License-Identifier: GPL-3.0-or-later
// Kernel set-up, normalisation, duplicate merging and the polynomial basis shared by the
// direct and the greedy RBF.
#include "meshmorph/deform/rbf_setup.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <mutex>
#include <set>
#include <sstream>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/rbf_evaluator.h"
#include "meshmorph/deform/rbf_setup.h"

namespace meshmorph
{

namespace detail
{

namespace
{

//! The log line for a polynomial the handles cannot determine, once per process for each
//! (terms, kept) pair: a 2D case's handles are coplanar in every fit of a design set-up and
//! every step of a morph, and the same line for each would bury the log.
void say_polynomial_terms_dropped(std::size_t terms, Eigen::Index kept)
{
    static std::mutex mutex;
    static std::set<std::pair<std::size_t, Eigen::Index>> said;
    {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!said.insert({terms, kept}).second)
            return;
    }
    log::info() << "RBF: handles do not determine all " << terms
                << " polynomial terms (coplanar, collinear or too few); keeping " << kept
                << " (said once: later fits of this run with the same handles' shape keep "
                   "them without a word)";
}

} // namespace

RbfKernelSetup rbf_kernel_setup(const RbfSettings& s)
{
    RbfKernelSetup k;
    const auto need_polynomial = [&](const char* why)
    {
        if (!s.polynomial)
            throw InvalidInput("RBF kernel " + to_string(s.kernel) +
                               " needs the polynomial term (" + why + ")");
    };
    const auto positive = [](double v, const char* what)
    {
        if (!(v > 0.0) || !std::isfinite(v))
        {
            std::ostringstream m;
            m << "RBF " << what << " must be a finite number > 0 (got " << v << ")";
            throw InvalidInput(m.str());
        }
    };
    int order = 0;
    switch (s.kernel)
    {
    case RbfKernel::triharmonic:
        order = 3;
        break;
    case RbfKernel::biharmonic:
        order = 2;
        break;
    case RbfKernel::polyharmonic:
        order = s.polyharmonic_order;
        if (order < 2)
            throw InvalidInput("RBF polyharmonic order k must be >= 2 (phi = r^(2k-3); got k = " +
                               std::to_string(order) + ")");
        if (order > 6)
            throw InvalidInput(
                "RBF polyharmonic order k must be <= 6 (got k = " + std::to_string(order) + ")");
        break;
    case RbfKernel::gaussian:
    case RbfKernel::inverse_multiquadric:
        positive(s.shape_parameter, "shape parameter");
        k.params.type = s.kernel == RbfKernel::gaussian ? KernelType::gaussian
                                                        : KernelType::inverse_multiquadric;
        k.params.eps = s.shape_parameter;
        k.degree = s.polynomial ? 1 : -1;
        break;
    case RbfKernel::multiquadric:
        positive(s.shape_parameter, "shape parameter");
        need_polynomial("conditionally positive definite of order 1");
        k.params.type = KernelType::multiquadric;
        k.params.eps = s.shape_parameter;
        k.degree = 1;
        k.sign = -1.0;
        break;
    case RbfKernel::wendland_c2:
        positive(s.support_radius, "support radius (Wendland C2)");
        k.params.type = KernelType::wendland_c2;
        k.params.support = s.support_radius;
        k.degree = s.polynomial ? 1 : -1;
        break;
    }
    if (order > 0)
    {
        need_polynomial("polyharmonic splines are only conditionally positive definite");
        k.params.type = KernelType::polyharmonic;
        k.params.power = 2 * order - 3;
        // r^(2k-3) is conditionally definite of order k-1 with sign (-1)^(k-1): the
        // null-space matrix is positive definite for r^3 and negative definite for r, r^5.
        k.degree = std::max(1, order - 2);
        k.sign = (order - 1) % 2 == 0 ? 1.0 : -1.0;
    }
    if (!(s.duplicate_tolerance >= 0.0))
        throw InvalidInput("RBF duplicate tolerance must be >= 0");
    if (!(s.polynomial_rank_tolerance > 0.0 && s.polynomial_rank_tolerance < 1.0))
        throw InvalidInput("RBF polynomial rank tolerance must be in (0, 1)");
    return k;
}

Normalisation normalisation_of(const Eigen::Ref<const Points>& x)
{
    Normalisation n;
    const Vector3 lo = x.colwise().minCoeff().transpose();
    const Vector3 hi = x.colwise().maxCoeff().transpose();
    n.centre = 0.5 * (lo + hi);
    n.scale = (hi - lo).maxCoeff();
    if (!(n.scale > 0.0))
        n.scale = std::max(1.0, n.centre.cwiseAbs().maxCoeff());
    return n;
}

namespace
{
std::string point_text(const Eigen::Ref<const Points>& p, Eigen::Index i)
{
    std::ostringstream s;
    s.precision(17);
    s << '(' << p(i, 0) << ' ' << p(i, 1) << ' ' << p(i, 2) << ')';
    return s.str();
}
} // namespace

RbfModel normalised_model(const RbfKernelSetup& setup, const Eigen::Ref<const Points>& points)
{
    RbfModel model;
    model.kernel = setup.params;
    const Normalisation nrm = normalisation_of(points);
    model.centre = nrm.centre;
    model.scale = nrm.scale;
    model.kernel.eps = setup.params.eps * nrm.scale;
    model.kernel.support = setup.params.support / nrm.scale;
    return model;
}

MergedHandles merge_duplicates(const Eigen::Ref<const Points>& handles,
                               const Eigen::Ref<const Points>& normalised,
                               const Eigen::Ref<const Points>& displacements, double tolerance)
{
    MergedHandles out;
    const Eigen::Index m = handles.rows();
    out.representative.assign(std::size_t(m), -1);
    double max_disp = 0.0;
    for (Eigen::Index i = 0; i < m; ++i)
        max_disp = std::max(max_disp, displacements.row(i).norm());
    const double disp_tol = tolerance * max_disp;
    // Cells a thousand times the tolerance (normalised coordinates are O(1), so the keys
    // stay small): a handle's tolerance box nearly always lies in one cell.
    const double radius = std::max(tolerance, 1e-14);
    const UniformGrid grid(normalised, 1000.0 * radius);
    std::vector<Eigen::Index> kept;
    for (Eigen::Index i = 0; i < m; ++i)
    {
        Eigen::Index dup = -1; // the first handle it coincides with
        grid.for_each_within(normalised(i, 0), normalised(i, 1), normalised(i, 2), radius,
                             [&](Eigen::Index j)
                             {
                                 if (j < i && (dup < 0 || j < dup) &&
                                     (normalised.row(i) - normalised.row(j)).norm() <= tolerance)
                                     dup = j;
                             });
        if (dup < 0)
        {
            out.representative[std::size_t(i)] = Index(kept.size());
            out.first.push_back(Index(i));
            kept.push_back(i);
            continue;
        }
        if ((displacements.row(i) - displacements.row(dup)).norm() > disp_tol)
            throw InvalidInput("handles " + std::to_string(dup) + " " + point_text(handles, dup) +
                               " and " + std::to_string(i) + " " + point_text(handles, i) +
                               " coincide but have different displacements " +
                               point_text(displacements, dup) + " and " +
                               point_text(displacements, i));
        out.representative[std::size_t(i)] = out.representative[std::size_t(dup)];
    }
    out.centres.resize(Eigen::Index(kept.size()), 3);
    out.displacements.resize(Eigen::Index(kept.size()), 3);
    for (std::size_t k = 0; k < kept.size(); ++k)
    {
        out.centres.row(Eigen::Index(k)) = normalised.row(kept[k]);
        out.displacements.row(Eigen::Index(k)) = displacements.row(kept[k]);
    }
    return out;
}

void choose_polynomial(RbfModel& model, int degree, const Eigen::Ref<const Points>& centres,
                       double rank_tolerance)
{
    model.exponents.clear();
    model.rotation.setIdentity();
    if (degree < 0)
        return;
    const Eigen::Index m = centres.rows();
    // Principal frame: a degenerate (coplanar / collinear) handle set has a coordinate that
    // is ~0 there, so the pivoted QR drops exactly the monomials that involve it.
    const Eigen::RowVector3d mean = centres.colwise().mean();
    const Eigen::MatrixXd d = centres.rowwise() - mean;
    const Eigen::Matrix3d cov = d.transpose() * d;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    Eigen::Matrix3d R = eig.eigenvectors().rowwise().reverse(); // largest extent first
    if (R.determinant() < 0)
        R.col(2) = -R.col(2);
    model.rotation = R;
    const std::vector<std::array<int, 3>> all = monomials(degree);
    model.exponents = all;
    const Eigen::MatrixXd P = model.polynomial_matrix(centres) / std::sqrt(double(m));
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(P);
    qr.setThreshold(rank_tolerance);
    const Eigen::Index rank = qr.rank();
    std::vector<Eigen::Index> keep;
    for (Eigen::Index k = 0; k < rank; ++k)
        keep.push_back(qr.colsPermutation().indices()[k]);
    std::sort(keep.begin(), keep.end());
    model.exponents.clear();
    for (Eigen::Index k : keep)
        model.exponents.push_back(all[std::size_t(k)]);
    if (rank < Eigen::Index(all.size()))
        say_polynomial_terms_dropped(all.size(), rank);
}

} // namespace detail

} // namespace meshmorph
