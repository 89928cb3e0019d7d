// SPDX-License-Identifier: GPL-3.0-or-later
// One held fit for every design variable: chosen on a combination, applied per variant.
#include "meshmorph/design/shared_design_fit.h"

#include <cstdint>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/morph/deformation_methods.h"
#include "meshmorph/morph/morph_steps.h"
#include "meshmorph/morph/point_morph.h"

namespace meshmorph::design
{

namespace
{

//! +1 or -1, fixed by j and spread evenly (the top bit of a multiplicative hash).
double choosing_sign(std::size_t j)
{
    const std::uint64_t h = std::uint64_t(j + 1) * 0x9E3779B97F4A7C15ULL;
    return (h >> 63) != 0 ? -1.0 : 1.0;
}

double largest(const Points& values)
{
    return values.rows() > 0 ? values.rowwise().norm().maxCoeff() : 0.0;
}

} // namespace

SparsePrescription sparse_prescription(const Points& dense)
{
    SparsePrescription p;
    for (Eigen::Index i = 0; i < dense.rows(); ++i)
        if (!dense.row(i).isZero(0.0))
            p.rows.push_back(Index(i));
    p.values.resize(Eigen::Index(p.rows.size()), 3);
    for (std::size_t k = 0; k < p.rows.size(); ++k)
        p.values.row(Eigen::Index(k)) = dense.row(p.rows[k]);
    return p;
}

std::string why_not_shared(const morph::Constraints& first, const morph::Constraints& c)
{
    if (c.points != first.points)
        return "the variables constrain different points (a handle variable's handle is free "
               "in the others)";
    if (c.slip_points != first.slip_points)
        return "the variables let different points slip";
    return "";
}

std::string why_not_shared(const morph::Constraints& c, bool parallel)
{
    if (parallel)
        return "-parallel (a shared set-up is serial for now)";
    if (c.wedge)
        return "a wedge case (its transpose is not available yet)";
    if (!c.cyclic_pairs.empty())
        return "cyclic patches (their transpose is not available yet)";
    if (c.jump_smoothing == morph::JumpSmoothingMode::on)
        return "jumpSmoothing (its transpose is not available yet)";
    return "";
}

SharedDesignFit::SharedDesignFit(const PolyMesh& mesh, const morph::DeformationSettings& settings,
                                 morph::Constraints constraints,
                                 std::vector<SparsePrescription> units)
    : mesh_(mesh), constraints_(std::move(constraints)), units_(std::move(units))
{
    if (const std::string why = why_not_shared(constraints_, false); !why.empty())
        throw InvalidInput("designBasis shared: not available for " + why +
                           "; use designBasis fields");
    for (const SparsePrescription& u : units_)
        for (const Index r : u.rows)
            if (r < 0 || r >= Index(constraints_.points.size()))
                throw InvalidInput("designBasis shared: a prescription row out of range");
    morph::DeformationSettings linear = settings;
    linear.limit = false;
    const Index n_fit = constraints_.n_prescribed_points + constraints_.n_slip_points;
    const Points& x = mesh.points;
    held_ = std::make_unique<HeldFits>([linear, &x, n_fit]
                                       { return morph::make_deformation(linear, x, n_fit); });
    const Stopwatch clock;
    constraints_.displacements = choosing_prescription();
    log::info() << "Choosing the shared fit of " << units_.size()
                << " variables on a combination of their prescriptions";
    const std::unique_ptr<SpaceDeformation> view = held_->view();
    morph::PointMorph pm = morph::morph_points(mesh_, constraints_, *view, true, false);
    morph::measure_constraint_error(constraints_, mesh_.points, pm, nullptr);
    report_ = pm.report;
    max_constraint_error_ = pm.max_constraint_error;
    relative_constraint_error_ = pm.relative_constraint_error;
    held_->freeze();
    choice_seconds_ = clock.seconds();
    log::info() << "Shared fit: " << report_.num_centres << " centres, " << report_.jump_constraints
                << " jump constraints left to the correction, " << format_seconds(choice_seconds_)
                << " s";
}

Points SharedDesignFit::choosing_prescription() const
{
    Points sum = Points::Zero(Eigen::Index(constraints_.points.size()), 3);
    double scale = 0.0;
    for (std::size_t j = 0; j < units_.size(); ++j)
    {
        const double size = largest(units_[j].values);
        if (!(size > 0.0))
            continue;
        scale = std::max(scale, size);
        const double weight = choosing_sign(j) / size;
        for (std::size_t k = 0; k < units_[j].rows.size(); ++k)
            sum.row(units_[j].rows[k]) += weight * units_[j].values.row(Eigen::Index(k));
    }
    const double size = largest(sum);
    if (!(size > 0.0))
        throw InvalidInput("designBasis shared: no variable moves any point");
    return sum * (scale / size);
}

Points SharedDesignFit::prescription(const std::vector<double>& a) const
{
    if (a.size() != units_.size())
        throw InvalidInput(std::to_string(a.size()) + " amplitudes for " +
                           std::to_string(units_.size()) + " variables");
    Points p = Points::Zero(Eigen::Index(constraints_.points.size()), 3);
    for (std::size_t j = 0; j < units_.size(); ++j)
    {
        if (a[j] == 0.0)
            continue;
        for (std::size_t k = 0; k < units_[j].rows.size(); ++k)
            p.row(units_[j].rows[k]) += a[j] * units_[j].values.row(Eigen::Index(k));
    }
    return p;
}

Points SharedDesignFit::apply(const Points& prescription)
{
    if (prescription.rows() != Eigen::Index(constraints_.points.size()))
        throw InvalidInput("designBasis shared: a prescription of the wrong size");
    if (prescription.isZero(0.0))
        return Points::Zero(mesh_.n_points(), 3); // the held fit of nothing is nothing
    constraints_.displacements = prescription;
    const std::unique_ptr<SpaceDeformation> view = held_->view();
    return morph::morph_points(mesh_, constraints_, *view, true, false).displacement;
}

std::vector<double> SharedDesignFit::transpose(const Points& g)
{
    // The held map is linear: its transpose does not depend on the data it was last fitted
    // to, so the constraints keep those (the last variant's, or the choosing prescription)
    // and the held fits refit nothing.
    const morph::FieldMaker make = [this] { return held_->view(); };
    const Points at_points = morph::morph_points_transpose(mesh_, constraints_, make, g);
    std::vector<double> out(units_.size(), 0.0);
    for (std::size_t j = 0; j < units_.size(); ++j)
    {
        double sum = 0.0;
        for (std::size_t k = 0; k < units_[j].rows.size(); ++k)
            sum += units_[j]
                       .values.row(Eigen::Index(k))
                       .dot(at_points.row(constraints_.points[std::size_t(units_[j].rows[k])]));
        out[j] = sum;
    }
    return out;
}

} // namespace meshmorph::design
