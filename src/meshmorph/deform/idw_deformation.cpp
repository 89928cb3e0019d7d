// SPDX-License-Identifier: GPL-3.0-or-later
// IDW interpolation: normalisation, the handle tree, threaded evaluation.
#include "meshmorph/deform/idw_deformation.h"

#include <cmath>
#include <optional>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/idw_tree.h"

namespace meshmorph
{

struct IdwDeformation::Impl
{
    IdwSettings settings;
    FitReport report;
    Vector3 centre = Vector3::Zero();
    double scale = 1.0; //!< L: the handles' bounding-box diagonal
    std::optional<detail::IdwTree> tree;
    Points handles, displacements; //!< as fitted, for write_field()
    std::vector<char> quiet;       //!< as fitted (see fit())
};

IdwDeformation::IdwDeformation(const IdwSettings& settings) : impl_(std::make_unique<Impl>())
{
    if (settings.far_exponent < 1 || settings.near_exponent <= settings.far_exponent)
        throw InvalidInput("IDW: exponents must satisfy 1 <= a < b (got a = " +
                           std::to_string(settings.far_exponent) +
                           ", b = " + std::to_string(settings.near_exponent) + ")");
    if (!(settings.alpha > 0.0) || !(settings.theta >= 0.0 && settings.theta < 1.0))
        throw InvalidInput("IDW: alpha must be > 0 and theta in [0, 1)");
    impl_->settings = settings;
}

IdwDeformation::~IdwDeformation() = default;
IdwDeformation::IdwDeformation(IdwDeformation&&) noexcept = default;
IdwDeformation& IdwDeformation::operator=(IdwDeformation&&) noexcept = default;

void IdwDeformation::fit(const Eigen::Ref<const Points>& handles,
                         const Eigen::Ref<const Points>& displacements)
{
    fit(handles, displacements, {});
}

void IdwDeformation::refit(const Eigen::Ref<const Points>& displacements)
{
    if (!is_fitted())
        throw InvalidInput("IDW: refit before fit");
    const Points handles = impl_->handles;
    const std::vector<char> quiet = impl_->quiet;
    fit(handles, displacements, quiet);
}

void IdwDeformation::fit(const Eigen::Ref<const Points>& handles,
                         const Eigen::Ref<const Points>& displacements,
                         const std::vector<char>& quiet)
{
    detail::check_fit_arguments(handles, displacements);
    if (!quiet.empty() && Index(quiet.size()) != Index(handles.rows()))
        throw InvalidInput("IDW: " + std::to_string(quiet.size()) + " quiet flags for " +
                           std::to_string(handles.rows()) + " handles");
    Impl& d = *impl_;
    d.tree.reset();
    const Vector3 lo = handles.colwise().minCoeff().transpose();
    const Vector3 hi = handles.colwise().maxCoeff().transpose();
    d.centre = 0.5 * (lo + hi);
    d.scale = (hi - lo).norm();
    if (!(d.scale > 0.0))
        d.scale = 1.0; // a single handle (or all coincident): d is that handle's value
    // The same operations as in evaluate(), so a point that is a handle lands on it exactly.
    const Points normalised = (handles.rowwise() - d.centre.transpose()) * (1.0 / d.scale);
    const IdwSettings& s = d.settings;
    const detail::IdwWeight weight{s.far_exponent, s.near_exponent,
                                   std::pow(s.alpha, s.near_exponent)};
    d.tree.emplace(normalised, Points(displacements), weight, s.theta, quiet);
    d.handles = handles;
    d.displacements = displacements;
    d.quiet = quiet;
    d.report = FitReport{};
    d.report.method = "idw";
    d.report.solver = s.theta > 0.0 ? "tree (second-order far field)" : "direct sum";
    d.report.num_handles = static_cast<Index>(handles.rows());
    d.report.num_centres = d.report.num_handles;
    d.report.max_displacement = displacements.rowwise().norm().maxCoeff();
}

void IdwDeformation::write_field(FieldWriter& out) const
{
    if (!impl_->tree)
        throw InvalidInput("IDW: write_field before fit");
    if (const QueryRegion* region = out.region())
    {
        // The region in the tree's normalised units.
        const Impl& d = *impl_;
        out.put(FieldKind::idw_local);
        out.put(d.settings);
        out.put_matrix(d.centre);
        out.put(d.scale);
        out.put(d.report.max_displacement);
        out.put(d.report.num_handles);
        const Vector3 lo =
            (Vector3(region->lo[0], region->lo[1], region->lo[2]) - d.centre) / d.scale;
        const Vector3 hi =
            (Vector3(region->hi[0], region->hi[1], region->hi[2]) - d.centre) / d.scale;
        d.tree->write_essential(out, lo, hi);
        return;
    }
    out.put(FieldKind::idw);
    out.put(impl_->settings);
    out.put_matrix(impl_->handles);
    out.put_matrix(impl_->displacements);
    out.put_vector(impl_->quiet);
}

IdwDeformation IdwDeformation::read_local(FieldReader& in)
{
    const IdwSettings settings = in.get<IdwSettings>();
    IdwDeformation idw(settings);
    Impl& d = *idw.impl_;
    d.centre = in.get_matrix<Vector3>();
    d.scale = in.get<double>();
    const double max_displacement = in.get<double>();
    const Index handles = in.get<Index>();
    const detail::IdwWeight weight{settings.far_exponent, settings.near_exponent,
                                   std::pow(settings.alpha, settings.near_exponent)};
    d.tree.emplace(detail::IdwTree::read_essential(in, weight, settings.theta));
    d.report.method = "idw";
    d.report.solver = "tree (locally essential)";
    d.report.num_handles = d.report.num_centres = handles;
    d.report.max_displacement = max_displacement;
    return idw;
}

void IdwDeformation::evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const
{
    const Impl& d = *impl_;
    detail::check_evaluate_arguments(d.tree.has_value(), points, out, "IDW");
    const Points normalised = (points.rowwise() - d.centre.transpose()) * (1.0 / d.scale);
    Points result;
    d.tree->weighted_mean(normalised, result);
    out = result;
}

Points IdwDeformation::transpose(const Eigen::Ref<const Points>& points,
                                 const Eigen::Ref<const Points>& weights) const
{
    const Impl& d = *impl_;
    detail::check_transpose_arguments(d.tree.has_value(), points, weights, "IDW");
    if (d.handles.rows() == 0)
        throw InvalidInput("IDW: no transpose for a field read for a region (-parallel)");
    const Points normalised = (points.rowwise() - d.centre.transpose()) * (1.0 / d.scale);
    Points adjoint;
    d.tree->weighted_mean_transpose(normalised, Points(weights), adjoint);
    return adjoint;
}

const FitReport& IdwDeformation::report() const
{
    return impl_->report;
}

bool IdwDeformation::is_fitted() const
{
    return impl_->tree.has_value();
}

} // namespace meshmorph
