// SPDX-License-Identifier: GPL-3.0-or-later
// The largest valid step: the bounds, the cubics' estimate, then the check around it.
#include "meshmorph/design/valid_step.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/parallel/communicator.h"
#include "meshmorph/quality/inversion_step.h"

namespace meshmorph::design
{

namespace
{

constexpr double infinity = std::numeric_limits<double>::infinity();

void check_direction(const DesignStudy& study, const std::vector<double>& p, double limit)
{
    if (p.size() != study.names().size())
        throw InvalidInput("the direction has " + std::to_string(p.size()) +
                           " components, the set-up has " + std::to_string(study.names().size()) +
                           " design variables");
    for (std::size_t j = 0; j < p.size(); ++j)
        if (!std::isfinite(p[j]))
            throw InvalidInput("the direction's component for " + study.names()[j] +
                               " is not finite");
    if (std::all_of(p.begin(), p.end(), [](double v) { return v == 0.0; }))
        throw InvalidInput("the direction is zero: no step to search");
    if (!(limit > 0.0))
        throw InvalidInput("the step limit must be positive (it is " + format_scalar(limit, 6) +
                           ")");
}

//! The step at which a + t p first reaches a variable's bound (+infinity: never); `name`
//! receives that variable.
double bound_step(const DesignStudy& study, const std::vector<double>& a,
                  const std::vector<double>& p, std::string& name)
{
    double step = infinity;
    for (std::size_t j = 0; j < p.size(); ++j)
    {
        const auto& b = study.header().bounds[j];
        if (!b || p[j] == 0.0)
            continue;
        const double t = ((p[j] > 0.0 ? b->second : b->first) - a[j]) / p[j];
        if (t < step)
        {
            step = std::max(t, 0.0);
            name = study.names()[j];
        }
    }
    return step;
}

//! a + t p, kept within the bounds (the step to a bound lands on it, not a rounding past it).
std::vector<double> stepped(const DesignStudy& study, const std::vector<double>& a,
                            const std::vector<double>& p, double t)
{
    std::vector<double> x(a.size());
    for (std::size_t j = 0; j < a.size(); ++j)
    {
        x[j] = a[j] + t * p[j];
        if (const auto& b = study.header().bounds[j])
            x[j] = std::clamp(x[j], b->first, b->second);
    }
    return x;
}

//! The cubics' model of the first inversion along dx = sum_j p_j F_j, from the design in
//! the study's mesh. The first estimate visits every cell; it keeps as candidates the cells
//! estimated to invert within 4 times the first estimate, and later estimates (from a later
//! step, with checkMesh's centres there) revisit only those: a cell estimated far later is
//! unlikely to be first, and if it is, the check of the estimate says so.
class InversionModel
{
public:
    InversionModel(const DesignStudy& study, Points dx) : study_(study), dx_(std::move(dx)) {}

    //! The first estimate, over all cells; sets the candidates.
    double first(double limit)
    {
        const std::vector<double> steps =
            cell_inversion_steps(mesh(), study_.faces_of_cells(), geometry(), dx_, limit, nullptr);
        double t = steps.empty() ? infinity : *std::min_element(steps.begin(), steps.end());
        t = reduced(t);
        for (std::size_t c = 0; c < steps.size(); ++c)
            if (steps[c] <= 4.0 * t)
                candidates_.push_back(Index(c));
        return t;
    }

    //! An estimate from the design now in the study's mesh, over the candidates.
    double again(double limit)
    {
        const std::vector<double> steps = cell_inversion_steps(
            mesh(), study_.faces_of_cells(), geometry(), dx_, limit, &candidates_);
        return reduced(steps.empty() ? infinity : *std::min_element(steps.begin(), steps.end()));
    }

private:
    const PolyMesh& mesh() const { return study_.design_case().foam.mesh; }
    MeshGeometry geometry() const { return compute_geometry(mesh(), study_.faces_of_cells()); }
    double reduced(double local) const
    {
        return study_.design_case().parallel ? parallel::Communicator::world().min(local) : local;
    }

    const DesignStudy& study_;
    Points dx_;
    std::vector<Index> candidates_;
};

//! Narrow a bracket: `accepted` holds at lo, not at hi; to valid_step_tolerance.
void bisect(const std::function<bool(double)>& accepted, double& lo, double& hi)
{
    while (hi - lo > valid_step_tolerance * hi)
    {
        const double mid = 0.5 * (lo + hi);
        (accepted(mid) ? lo : hi) = mid;
    }
}

//! From a valid r.step, step on in growing increments (the first `increment`) until the
//! check fails (r.invalid_above) or `end` is reached (capped: 4^30 increments).
void grow_bracket(const std::function<bool(double)>& valid, double increment, double end,
                  ValidStep& r)
{
    for (int k = 0; k < 30 && r.step < end; ++k)
    {
        const double next = std::min(r.step + increment, end);
        if (!valid(next))
        {
            r.invalid_above = next;
            return;
        }
        r.step = next;
        increment *= 4.0;
    }
}

//! March towards the first inversion from a valid r.step: check the cubics' estimate; where
//! it is valid, estimate again from there, with checkMesh's centres at that step (the cubic
//! is exact at its start, so each estimate is closer than the last). Stops at an invalid
//! estimate (r.invalid_above), at `end`, or when the next estimate is within the bracket's
//! tolerance of the step. \return the last estimate.
double march(InversionModel& model, const std::function<bool(double)>& valid, double estimate,
             double end, ValidStep& r)
{
    for (int k = 0; k < 12 && estimate < end; ++k)
    {
        if (!valid(estimate))
        {
            r.invalid_above = estimate;
            break;
        }
        r.step = estimate; // (the study's mesh now holds it: the next estimate starts there)
        estimate = r.step + model.again(end - r.step);
        if (estimate - r.step <= valid_step_tolerance * r.step)
            break; // the model puts the inversion within the bracket's width
    }
    return estimate;
}

//! Keep the step where the check's maximum non-orthogonality is at most `theta` degrees.
void limit_non_orthogonality(DesignStudy& study, const std::vector<double>& a,
                             const std::vector<double>& p, double theta, ValidStep& r)
{
    double at_step = 0.0, at_lo = 0.0; // the maximum at the last step checked, at lo
    const auto within = [&](double t)
    {
        ++r.checks;
        const VariantResult v = study.evaluate(stepped(study, a, p, t), false);
        at_step = v.after.max_non_orthogonality;
        const bool accepted = !v.refused && at_step <= theta;
        if (accepted)
            at_lo = at_step; // (an accepted step always becomes lo)
        return accepted;
    };
    if (!within(0.0))
        throw InvalidInput("the start's maximum non-orthogonality (" + format_scalar(at_step, 4) +
                           " degrees) is already above the limit of " + format_scalar(theta, 4) +
                           " degrees: search from a better design or raise the limit");
    double lo = 0.0, hi = infinity;
    if (std::isfinite(r.step))
        for (int k = 1; k <= 8 && !std::isfinite(hi); ++k) // samples up to the valid step
        {
            const double t = r.step * k / 8.0;
            (within(t) ? lo : hi) = t;
        }
    else
        for (double t = 1.0; t < 1e300 && !std::isfinite(hi); t *= 2.0) // no end: double
            (within(t) ? lo : hi) = t;
    r.max_non_orthogonality = at_lo;
    if (!std::isfinite(hi))
        return; // within the limit up to the valid step
    bisect(within, lo, hi);
    r.step = lo;
    r.invalid_above = hi;
    r.max_non_orthogonality = at_lo;
    r.limited_by = "nonOrthogonality";
    r.bound_variable.clear();
}

} // namespace

ValidStep largest_valid_step(DesignStudy& study, const std::vector<double>& a,
                             const std::vector<double>& direction, double limit,
                             double max_non_orthogonality)
{
    const Stopwatch clock;
    study.check_amplitudes(a);
    check_direction(study, direction, limit);
    if (!(max_non_orthogonality > 0.0))
        throw InvalidInput("the non-orthogonality limit must be above 0 degrees (it is " +
                           format_scalar(max_non_orthogonality, 4) + ")");
    ValidStep r;
    const auto valid = [&](double t)
    {
        ++r.checks;
        return study.is_valid(stepped(study, a, direction, t));
    };
    if (!valid(0.0))
        throw InvalidInput("the start of the step search is not valid (it has more "
                           "negative-volume cells or wrongly oriented face pyramids than the "
                           "set-up's mesh): search from a valid design");
    const double to_bound = bound_step(study, a, direction, r.bound_variable);
    const double end = std::min(limit, to_bound);
    r.limited_by = !std::isfinite(end) ? "none" : to_bound <= limit ? "bounds" : "limit";
    if (r.limited_by != "bounds")
        r.bound_variable.clear();
    InversionModel model(study, study.combine(direction)); // the points' rates along p
    r.estimate = model.first(end);                         // (the mesh holds a: valid(0))
    r.step = 0.0;
    r.invalid_above = infinity;
    const double last = march(model, valid, r.estimate, end, r);
    if (!std::isfinite(r.invalid_above)) // not bracketed yet
    {
        if (last < end) // converged just below a crossing, or out of marches
            grow_bracket(valid, valid_step_tolerance * std::max(r.step, r.estimate), end, r);
        else if (std::isfinite(end) && valid(end))
            r.step = end;
        else if (std::isfinite(end))
            r.invalid_above = end; // the estimates missed an inversion: bisect [step, end]
        else
            r.step = infinity; // no bound, no limit, and nothing inverts along p (by the cubics)
    }
    if (std::isfinite(r.invalid_above))
    {
        bisect(valid, r.step, r.invalid_above);
        r.limited_by = "inversion";
        r.bound_variable.clear();
    }
    if (max_non_orthogonality < 90.0)
        limit_non_orthogonality(study, a, direction, max_non_orthogonality, r);
    r.seconds = clock.seconds();
    return r;
}

} // namespace meshmorph::design
