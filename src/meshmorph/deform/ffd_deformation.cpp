// SPDX-License-Identifier: GPL-3.0-or-later
// Classic FFD on a uniform cubic B-spline lattice.
#include "meshmorph/deform/ffd_deformation.h"

#include <cstddef>
#include <string>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/field_stream.h"

namespace meshmorph
{

FfdLattice make_lattice(const FfdSettings& settings, const Eigen::Ref<const Points>& points)
{
    if (settings.box)
        return FfdLattice(*settings.box, settings.control_points);
    return FfdLattice::bounding(points, settings.control_points, settings.margin);
}

FfdDeformation::FfdDeformation(const FfdLattice& lattice, FfdOutside outside)
    : lattice_(lattice), outside_(outside)
{
}

void FfdDeformation::write_field(FieldWriter& out) const
{
    if (!fitted_)
        throw InvalidInput("FFD: write_field before the control displacements are set");
    out.put(FieldKind::ffd);
    out.put_matrix(lattice_.box().origin);
    out.put_matrix(lattice_.box().axes);
    for (int a = 0; a < 3; ++a)
        out.put_vector(lattice_.knots(a));
    out.put(outside_);
    out.put_matrix(control_displacements_);
}

void FfdDeformation::set_control_displacements(const Eigen::Ref<const Points>& displacements)
{
    if (displacements.rows() != lattice_.size())
        throw InvalidInput("FFD: " + std::to_string(displacements.rows()) +
                           " control displacements for a lattice of " +
                           std::to_string(lattice_.size()) + " control points");
    detail::require_finite(displacements, "FFD control displacement");
    control_displacements_ = displacements;
    fitted_ = true;
    report_ = FitReport{};
    report_.method = "ffd";
    report_.solver = "none (control points moved directly)";
    report_.num_handles = lattice_.size();
    report_.num_centres = lattice_.size();
    for (Eigen::Index i = 0; i < displacements.rows(); ++i)
        report_.max_displacement = std::max(report_.max_displacement, displacements.row(i).norm());
}

void FfdDeformation::fit(const Eigen::Ref<const Points>& handles,
                         const Eigen::Ref<const Points>& displacements)
{
    detail::check_fit_arguments(handles, displacements);
    if (handles.rows() != lattice_.size())
        throw InvalidInput("FFD fit: the handles must be the " + std::to_string(lattice_.size()) +
                           " lattice control points; got " + std::to_string(handles.rows()) +
                           " (use DM-FFD for arbitrary handles)");
    const double tol = 1e-9 * lattice_.box().axes.colwise().norm().maxCoeff();
    for (Eigen::Index i = 0; i < handles.rows(); ++i)
        if ((handles.row(i) - lattice_.control_points().row(i)).norm() > tol)
            throw InvalidInput("FFD fit: handle " + std::to_string(i) +
                               " is not lattice control point " + std::to_string(i) +
                               " (use DM-FFD for arbitrary handles)");
    set_control_displacements(displacements);
}

void FfdDeformation::evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const
{
    detail::check_evaluate_arguments(fitted_, points, out, "FFD");
    const Eigen::Index n = points.rows();
#pragma omp parallel for schedule(dynamic, 256) if (points.rows() > 2000)
    for (Eigen::Index i = 0; i < n; ++i)
    {
        Index idx[64];
        double w[64];
        const int count = lattice_.basis(points.row(i).transpose(), outside_, idx, w);
        // Scalar accumulators (not an array) keep the sums in registers.
        const double* cd = control_displacements_.data();
        double dx = 0.0, dy = 0.0, dz = 0.0;
        for (int k = 0; k < count; ++k)
        {
            const double* c = cd + 3 * static_cast<std::ptrdiff_t>(idx[k]);
            dx += w[k] * c[0];
            dy += w[k] * c[1];
            dz += w[k] * c[2];
        }
        out(i, 0) = dx;
        out(i, 1) = dy;
        out(i, 2) = dz;
    }
}

Eigen::MatrixXd FfdDeformation::basis_matrix(const Eigen::Ref<const Points>& points) const
{
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(points.rows(), lattice_.size());
#pragma omp parallel for schedule(dynamic, 256) if (points.rows() > 2000)
    for (Eigen::Index i = 0; i < points.rows(); ++i)
    {
        Index idx[64];
        double w[64];
        const int count = lattice_.basis(points.row(i).transpose(), outside_, idx, w);
        for (int k = 0; k < count; ++k)
            M(i, idx[k]) = w[k];
    }
    return M;
}

} // namespace meshmorph
