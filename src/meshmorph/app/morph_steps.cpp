// SPDX-License-Identifier: GPL-3.0-or-later
// The step loop: fractional prescriptions, refit on the moved mesh, check, halve on failure.
#include "meshmorph/app/morph_steps.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "meshmorph/app/banner.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/io/foam_dictionary.h"

namespace meshmorph::app
{

namespace
{

//! The constraints of one step: from the current points to fraction t of the motion.
Constraints step_constraints(const Constraints& c, const Points& x0, const Points& x, double t)
{
    Constraints step = c;
    step.displacements = prescribed_at(c, x0, t);
    for (std::size_t i = 0; i < c.points.size(); ++i)
        step.displacements.row(static_cast<Eigen::Index>(i)) -=
            x.row(c.points[i]) - x0.row(c.points[i]);
    return step;
}

std::string fraction(double t)
{
    std::ostringstream o;
    o.precision(4);
    o << t;
    return o.str();
}

} // namespace

StepSettings read_step_settings(const io::FoamDictionary& dict)
{
    StepSettings s;
    const io::FoamEntry* e = dict.find("steps");
    if (e == nullptr)
        return s;
    const std::vector<io::FoamValueToken>& t = e->tokens();
    if (t.size() == 1 && t[0].is_word() && t[0].text == "auto")
        return s;
    if (t.size() == 1 && t[0].is_label() && t[0].label >= 1 && t[0].label <= 10000)
    {
        s.steps = static_cast<int>(t[0].label);
        return s;
    }
    throw e->error("expected 'auto' or a number of steps from 1 to 10000");
}

std::string describe(const StepSettings& s)
{
    return s.steps == 0 ? "auto (halved on new invalid cells, down to 1/" +
                              std::to_string(s.max_steps) + " of the motion)"
                        : std::to_string(s.steps);
}

Points prescribed_at(const Constraints& c, const Points& x0, double t)
{
    Points d = t * c.displacements;
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        const Index r = i < c.rotation_of.size() ? c.rotation_of[i] : -1;
        if (r < 0)
            continue;
        Motion partial = c.rotations[static_cast<std::size_t>(r)];
        partial.angle_degrees *= t;
        Vector3 x = x0.row(c.points[i]).transpose();
        if (c.empty_normal) // as build_constraints: the reference empty plane
            x -= (c.empty_normal->dot(x) - c.empty_offset) * *c.empty_normal;
        Vector3 v = partial.displacement(x);
        if (c.empty_normal)
            v -= v.dot(*c.empty_normal) * *c.empty_normal;
        d.row(static_cast<Eigen::Index>(i)) = v.transpose();
    }
    return d;
}

void measure_constraint_error(const Constraints& c, const Points& x0, PointMorph& m)
{
    const Points prescribed = prescribed_at(c, x0, 1.0);
    double diag = 1.0;
    if (x0.rows() > 0)
        diag = (x0.colwise().maxCoeff() - x0.colwise().minCoeff()).norm();
    m.max_prescribed = 0.0;
    m.max_constraint_error = 0.0;
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        const Eigen::Index r = static_cast<Eigen::Index>(i);
        m.max_prescribed = std::max(m.max_prescribed, prescribed.row(r).norm());
        m.max_constraint_error = std::max(
            m.max_constraint_error, (m.displacement.row(c.points[i]) - prescribed.row(r)).norm());
    }
    m.relative_constraint_error = m.max_constraint_error / std::max(m.max_prescribed, 1e-12 * diag);
}

SteppedMorph morph_in_steps(const PolyMesh& mesh, const CompactList& cell_faces,
                            const Constraints& c, const StepSettings& settings,
                            const DeformationMaker& make, bool fit, const InvalidCells& before)
{
    SteppedMorph out;
    PolyMesh current = mesh; // topology shared by value; only points change
    const bool is_auto = settings.steps == 0 && fit;
    const double shortest = is_auto ? 1.0 / settings.max_steps : 1.0;
    double length = (settings.steps > 0 && fit) ? 1.0 / settings.steps : 1.0;
    double done = 0.0;
    while (done < 1.0)
    {
        const double to = std::min(1.0, done + length);
        const bool last_step = 1.0 - to < 1e-12;
        StepRecord record;
        record.from = done;
        record.to = last_step ? 1.0 : to;
        const Constraints step = step_constraints(c, mesh.points, current.points, record.to);
        std::unique_ptr<SpaceDeformation> deformation = make(current.points);
        PointMorph m = morph_points(current, step, *deformation, fit);
        record.centres = m.report.num_centres;
        record.max_global_residual =
            m.report.max_residual / std::max(m.report.max_displacement, 1e-300);
        record.fit_seconds = m.fit_seconds;
        record.evaluate_seconds = m.evaluate_seconds;
        PolyMesh trial = current;
        trial.points += m.displacement;
        const Stopwatch check_clock;
        MeshGeometry geometry = compute_geometry(trial, cell_faces);
        record.invalid = count_invalid_cells(trial, geometry);
        record.check_seconds = check_clock.seconds();
        const bool failed = record.invalid.worse_than(before);
        record.accepted = !(failed && is_auto && length > shortest * 1.5);
        out.steps.push_back(record);
        log::info() << "Step " << out.steps.size() << ": motion " << fraction(record.from) << " -> "
                    << fraction(record.to) << ", " << record.centres << " centres, "
                    << record.invalid.negative_volume_cells << " negative-volume cells, "
                    << record.invalid.wrong_pyramids << " wrongly oriented pyramids"
                    << (failed ? (record.accepted ? " (shortest step: stopping)"
                                                  : ": redone in half the length")
                               : "")
                    << " [fit " << format_seconds(record.fit_seconds) << " s, evaluate "
                    << format_seconds(record.evaluate_seconds) << " s, check "
                    << format_seconds(record.check_seconds) << " s]";
        if (!record.accepted)
        {
            length *= 0.5;
            continue;
        }
        current.points = std::move(trial.points);
        out.last = std::move(m);
        out.geometry = std::move(geometry);
        done = record.to;
        if (failed && is_auto)
            break; // even the shortest step inverts cells: the caller refuses the result
    }
    out.completed = done >= 1.0;
    out.displacement = current.points - mesh.points;
    out.points = std::move(current.points);
    return out;
}

} // namespace meshmorph::app
