// SPDX-License-Identifier: GPL-3.0-or-later
// The step loop: fractional prescriptions, refit on the moved mesh, check, halve on failure.
#include "meshmorph/morph/morph_steps.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/quality/inversion_step.h"

namespace meshmorph::morph
{

namespace
{

//! out = a + sign b (sign 1 or -1, so a - b exactly), rows on every thread: the morph's
//! point arrays (406k rows on the motorBike) otherwise take a serial pass each.
void add_rows(const Points& a, const Points& b, double sign, Points& out)
{
    out.resize(a.rows(), 3);
#pragma omp parallel for schedule(static) if (a.rows() > 4096)
    for (std::int64_t i = 0; i < std::int64_t(a.rows()); ++i)
        out.row(i) = a.row(i) + sign * b.row(i);
}

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

//! A fraction of the motion for the log (4 significant digits).
std::string format_fraction(double t)
{
    std::ostringstream o;
    o.precision(4);
    o << t;
    return o.str();
}

//! The repair of faces above maxNonOrtho, when it had work.
void log_non_ortho_repair(const NonOrthoRepair& r)
{
    if (r.skipped_cells > 0)
        log::info() << "    non-orthogonality not repaired: " << r.skipped_cells
                    << " cells with a face above maxNonOrtho, more than maxUntangleCells";
    else if (r.cells > 0 && r.points_moved == 0)
        log::info() << "    non-orthogonality not repaired: " << r.cells
                    << " cells with a face above maxNonOrtho, and no interior point near them "
                       "whose move improves them (in a 2D case every point is on the planes)";
    else if (r.cells > 0)
        log::info() << "    repaired non-orthogonality: " << r.cells
                    << " cells with a face above maxNonOrtho, by moving " << r.points_moved
                    << " interior points by up to " << r.max_move << "; " << r.cells_after
                    << " still above [" << format_seconds(r.seconds) << " s]";
}

//! One line per step as it happens: the motion fractions, the fit, the checks and the verdict.
void log_step(std::size_t number, const StepRecord& r, bool failed, bool redo, bool can_halve)
{
    std::string verdict;
    if (redo)
        verdict = ": redone in half the length";
    else if (failed && can_halve)
        verdict = " (the shortest step: the rest of the motion in one step, to be refused)";
    else if (failed)
        verdict = " (kept: the result will be refused)";
    if (r.untangle.skipped_cells > 0)
        log::info() << "    not untangled: " << r.untangle.skipped_cells
                    << " cells to repair, more than maxUntangleCells (the local repair is for "
                       "a few cells)";
    if (r.untangle.invalid_before > 0)
        log::info() << "    untangled " << r.untangle.invalid_before << " invalid cells by moving "
                    << r.untangle.points_moved << " interior points by up to "
                    << r.untangle.max_move << " (" << r.untangle.layers
                    << " layers of cells around them), " << r.untangle.invalid_after
                    << " still invalid"
                    << (r.untangle.below_target_after > r.untangle.invalid_after
                            ? ", " + std::to_string(r.untangle.below_target_after) +
                                  " below the repair's margin"
                            : std::string())
                    << " [" << format_seconds(r.untangle_seconds) << " s]";
    log_non_ortho_repair(r.non_ortho);
    log::info() << "Step " << number << ": motion " << format_fraction(r.from) << " -> "
                << format_fraction(r.to) << ", " << r.centres << " centres, "
                << r.invalid.negative_volume_cells << " negative-volume cells, "
                << r.invalid.wrong_pyramids << " wrongly oriented pyramids" << verdict << " [fit "
                << format_seconds(r.fit_seconds) << " s, evaluate "
                << format_seconds(r.evaluate_seconds) << " s, check "
                << format_seconds(r.check_seconds) << " s]";
}

//! `steps auto | N`.
StepSettings read_steps(const io::FoamDictionary& dict)
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

//! What the repair of a step needs from the unmorphed mesh, computed on first use. In a
//! morph in place the original points are kept aside from the mesh, which holds the steps'
//! points: their geometry is computed with them swapped in for the moment.
class OriginalState
{
public:
    //! The unmorphed mesh itself.
    OriginalState(const PolyMesh& mesh, const CompactList& cell_faces)
        : mesh_(&mesh), cell_faces_(cell_faces)
    {
    }
    //! In place: the working mesh (the topology) and the original points kept aside.
    OriginalState(PolyMesh& working, Points& aside, const CompactList& cell_faces)
        : mesh_(&working), working_(&working), aside_(&aside), cell_faces_(cell_faces)
    {
    }
    const Points& points() const { return aside_ ? *aside_ : mesh_->points; }
    const std::vector<double>& repair_targets()
    {
        if (targets_.empty())
            with_original_points(
                [&] {
                    targets_ = morph::repair_targets(*mesh_, cell_faces_,
                                                     compute_geometry(*mesh_, cell_faces_));
                });
        return targets_;
    }
    //! The unmorphed quality of the cells beyond maxNonOrtho (non_ortho_repair.h).
    void assess(NonOrthoCells& cells, double limit)
    {
        with_original_points([&]
                             { assess_non_orthogonal_cells(*mesh_, cell_faces_, limit, cells); });
    }
    //! Interior points (in a -parallel run also not on processor patches: a point shared
    //! with another rank must move alike on both, so the repair leaves it).
    const std::vector<char>& movable_points()
    {
        if (movable_.empty())
        {
            movable_ = boundary_point_mask(*mesh_);
            for (char& m : movable_)
                m = m ? 0 : 1;
        }
        return movable_;
    }

private:
    //! f() with mesh_ holding the unmorphed points (in place: swapped in for the moment).
    template <class F> void with_original_points(F f)
    {
        if (working_)
            std::swap(working_->points, *aside_);
        f();
        if (working_)
            std::swap(working_->points, *aside_);
    }

    const PolyMesh* mesh_;        //!< the topology, with the original points but in place
    PolyMesh* working_ = nullptr; //!< in place: the same mesh, to swap points in and out
    Points* aside_ = nullptr;     //!< in place: the original points
    const CompactList& cell_faces_;
    std::vector<double> targets_;
    std::vector<char> movable_;
};

//! The ranks of the run (one rank without a decomposition).
const parallel::Communicator& communicator(const Decomposition* decomposition)
{
    static const parallel::Communicator& serial = parallel::Communicator::world();
    return decomposition != nullptr && decomposition->is_distributed() ? *decomposition->comm
                                                                       : serial;
}

//! Invalid cells counted over every rank (a cell lives on one rank only).
InvalidCells global_invalid_cells(const PolyMesh& mesh, const MeshGeometry& geometry,
                                  const parallel::Communicator& comm,
                                  std::vector<char>& pyramid_errors)
{
    InvalidCells local = count_invalid_cells(mesh, geometry, &pyramid_errors);
    return {Index(comm.sum(std::int64_t(local.negative_volume_cells))),
            Index(comm.sum(std::int64_t(local.wrong_pyramids)))};
}

//! Untangle the step's new invalid cells in place and recount them, unless there are more
//! than `max_cells` cells to repair (over every rank).
void repair(PolyMesh& current, const CompactList& cell_faces, MeshGeometry& geometry,
            std::vector<char>& pyramid_errors, OriginalState& original, Index max_cells,
            StepRecord& record, const parallel::Communicator& comm)
{
    const Stopwatch clock;
    const Index to_repair = Index(comm.sum(std::int64_t(
        count_cells_below_target(current, cell_faces, geometry, original.repair_targets()))));
    if (to_repair > max_cells)
    {
        record.untangle.skipped_cells = to_repair;
        record.untangle_seconds = comm.max(clock.seconds());
        return;
    }
    record.untangle = untangle_cells(current, cell_faces, geometry, original.points(),
                                     original.repair_targets(), original.movable_points(), {});
    record.untangle.invalid_before = comm.sum(std::int64_t(record.untangle.invalid_before));
    record.untangle.invalid_after = comm.sum(std::int64_t(record.untangle.invalid_after));
    record.untangle.below_target_after = comm.sum(std::int64_t(record.untangle.below_target_after));
    record.untangle.points_moved = comm.sum(std::int64_t(record.untangle.points_moved));
    record.untangle.max_move = comm.max(record.untangle.max_move);
    record.untangle.layers = int(comm.max(std::int64_t(record.untangle.layers)));
    record.invalid = global_invalid_cells(current, geometry, comm, pyramid_errors);
    record.untangle_seconds = comm.max(clock.seconds());
}

//! Repair the cells with a face the valid step took above maxNonOrtho in place and recount
//! the invalid cells, unless there are more than maxUntangleCells such cells (over every rank).
void repair_non_ortho(PolyMesh& current, const CompactList& cell_faces, MeshGeometry& geometry,
                      std::vector<char>& pyramid_errors, OriginalState& original,
                      const StepSettings& settings, StepRecord& record,
                      const parallel::Communicator& comm)
{
    const Stopwatch clock;
    const double limit = settings.max_non_ortho;
    NonOrthoCells cells;
    cells.cells = cells_beyond_limit(current, geometry, limit);
    // Most morphs make no such face: one pass over the faces, nothing of the unmorphed mesh.
    if (comm.sum(std::int64_t(cells.cells.size())) == 0)
        return;
    cells.now = non_ortho_quality(current, cell_faces, geometry, cells.cells, limit);
    original.assess(cells, limit);
    NonOrthoRepair& r = record.non_ortho;
    const Index to_repair = Index(comm.sum(std::int64_t(cells.repaired.size())));
    if (to_repair > settings.max_untangle_cells)
        r.skipped_cells = to_repair;
    else if (to_repair > 0)
    {
        r = repair_non_orthogonality(current, cell_faces, geometry, original.points(), cells,
                                     limit);
        r.cells = to_repair;
        r.cells_after = Index(comm.sum(std::int64_t(r.cells_after)));
        r.points_moved = Index(comm.sum(std::int64_t(r.points_moved)));
        r.max_move = comm.max(r.max_move);
        record.invalid = global_invalid_cells(current, geometry, comm, pyramid_errors);
    }
    r.seconds = comm.max(clock.seconds());
}

} // namespace

StepSettings read_step_settings(const io::FoamDictionary& dict)
{
    StepSettings s = read_steps(dict);
    s.untangle = dict.get_or<bool>("untangle", true);
    if (const io::FoamEntry* e = dict.find("maxUntangleCells"))
    {
        const std::vector<io::FoamValueToken>& t = e->tokens();
        if (t.size() != 1 || !t[0].is_label() || t[0].label < 0)
            throw e->error("expected a number of cells (0 or more; default 1000)");
        s.max_untangle_cells = Index(t[0].label);
    }
    if (const io::FoamEntry* e = dict.find("maxNonOrtho"))
    {
        const std::vector<io::FoamValueToken>& t = e->tokens();
        if (t.size() == 1 && t[0].is_word("none"))
            s.max_non_ortho = 0.0;
        else if (t.size() == 1 && t[0].is_number() && t[0].scalar > 0.0 && t[0].scalar < 90.0)
            s.max_non_ortho = t[0].scalar;
        else
            throw e->error("expected an angle in degrees between 0 and 90 (default 70, "
                           "checkMesh's 'severely non-orthogonal') or none");
    }
    return s;
}

std::string describe(const StepSettings& s)
{
    return s.steps == 0 ? "auto (halved on new invalid cells, down to 1/" +
                              std::to_string(s.max_steps) + " of the motion)"
                        : std::to_string(s.steps);
}

Points prescribed_at(const Constraints& c, const Points& x0, double t)
{
    if (c.rotation_of.size() != c.points.size())
        throw std::logic_error("prescribed_at: rotation_of does not match the constraints");
    Points d = t * c.displacements;
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        const Index r = c.rotation_of[i];
        if (r < 0)
            continue;
        Motion partial = c.rotations[static_cast<std::size_t>(r)];
        partial.angle_degrees *= t;
        // As collect_claims: evaluated on the reference empty plane.
        const Vector3 x = evaluation_position(c.empty_planes, x0.row(c.points[i]).transpose());
        d.row(static_cast<Eigen::Index>(i)) =
            in_plane(c.empty_planes, partial.displacement(x)).transpose();
    }
    return d;
}

void measure_constraint_error(const Constraints& c, const Points& x0, PointMorph& m,
                              const Decomposition* decomposition)
{
    const parallel::Communicator& comm = communicator(decomposition);
    const Points prescribed = prescribed_at(c, x0, 1.0);
    const Points corners = bounding_corners(x0, decomposition);
    const double diag = x0.rows() > 0 ? (corners.row(1) - corners.row(0)).norm() : 1.0;
    m.max_prescribed = 0.0;
    m.max_constraint_error = 0.0;
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        const Eigen::Index r = static_cast<Eigen::Index>(i);
        m.max_prescribed = std::max(m.max_prescribed, prescribed.row(r).norm());
        m.max_constraint_error = std::max(
            m.max_constraint_error, (m.displacement.row(c.points[i]) - prescribed.row(r)).norm());
    }
    m.max_prescribed = comm.max(m.max_prescribed);
    m.max_constraint_error = comm.max(m.max_constraint_error);
    m.relative_constraint_error = m.max_constraint_error / std::max(m.max_prescribed, 1e-12 * diag);
}

namespace
{

//! One step's fit and evaluation; the record's fit figures set.
PointMorph fit_step(const PolyMesh& current, const Constraints& step, const DeformationMaker& make,
                    bool fit, const Decomposition* decomposition, StepRecord& record)
{
    std::unique_ptr<SpaceDeformation> deformation =
        make(bounding_corners(current.points, decomposition));
    PointMorph m = morph_points(current, step, *deformation, fit, false, decomposition);
    record.centres = m.report.num_centres;
    record.max_global_residual =
        m.report.max_fitted_residual / std::max(m.report.max_displacement, 1e-300);
    record.jump_constraints = m.report.jump_constraints;
    record.jump_smoothed_points = m.jump_smoothing.band_points;
    record.fit_seconds = m.fit_seconds;
    record.evaluate_seconds = m.evaluate_seconds;
    // The fitted field is spent when this returns: its memory (the greedy fit's factor, the
    // IDW tree: ~45 MB on the motorBike) goes to the check's geometry, which would otherwise
    // take fresh pages from the system (first touches cost ~2 ms per MB on a virtual machine).
    return m;
}

//! `jumpSmoothing auto`: keep the step's smoothed band or put its fitted field back
//! (jump_smoothing_guard.h), before the check counts the invalid cells; said in the log.
void choose_band(PolyMesh& current, const CompactList& cell_faces, MeshGeometry& geometry,
                 const Points& accepted, PointMorph& m, const parallel::Communicator& comm,
                 StepRecord& record)
{
    record.jump_choice = choose_jump_smoothing(current, cell_faces, geometry, accepted,
                                               m.jump_smoothing, m.displacement, comm);
    const JumpSmoothingChoice& c = record.jump_choice;
    if (!c.compared)
        return;
    if (!c.kept)
        record.jump_smoothed_points = 0;
    log::info() << "    jump smoothing " << (c.kept ? "kept" : "not kept")
                << ": near the jumps max non-orthogonality " << c.smoothed.max_non_ortho << " ("
                << c.smoothed.faces_above_70 << " faces above 70), without it "
                << c.fitted.max_non_ortho << " (" << c.fitted.faces_above_70 << ")"
                << (c.smoothed.invalid_cells + c.fitted.invalid_cells > 0
                        ? "; invalid cells " + std::to_string(c.smoothed.invalid_cells) +
                              ", without it " + std::to_string(c.fitted.invalid_cells)
                        : std::string());
}

//! The trial's check: its geometry, pyramid errors and invalid cells (in the record), after
//! the repair when `untangle` and it made cells invalid that were not before.
void check_step(PolyMesh& current, const CompactList& cell_faces, const InvalidCells& before,
                const StepSettings& settings, OriginalState& original,
                const parallel::Communicator& comm, StepRecord& record, MeshGeometry& geometry,
                std::vector<char>& pyramid_errors, const std::function<void()>& choose)
{
    const Stopwatch check_clock;
    geometry = compute_geometry(current, cell_faces);
    choose();
    record.invalid = global_invalid_cells(current, geometry, comm, pyramid_errors);
    record.check_seconds = comm.max(check_clock.seconds());
    if (settings.untangle && record.invalid.worse_than(before))
        repair(current, cell_faces, geometry, pyramid_errors, original, settings.max_untangle_cells,
               record, comm);
    if (settings.untangle && settings.max_non_ortho > 0.0 && !record.invalid.worse_than(before))
        repair_non_ortho(current, cell_faces, geometry, pyramid_errors, original, settings, record,
                         comm);
}

//! The next length after a trial of `length` whose repair was skipped (too many cells to
//! repair): halved at least once, and again while the cells it is predicted to fold are more
//! than `max_cells`. The refitted field of a shorter step from the same state is this one
//! scaled (the prescription scales, so do the greedy fit's tolerance and the limit), so each
//! cell inverts at about the same fraction of it (quality/inversion_step.h): lengths that
//! would fold too many cells to repair are skipped without a fit.
double halved_length(const PolyMesh& accepted, const CompactList& cell_faces,
                     const Points& displacement, double length, double shortest, Index max_cells,
                     const parallel::Communicator& comm)
{
    const std::vector<double> folds_at = cell_inversion_steps(
        accepted, cell_faces, compute_geometry(accepted, cell_faces), displacement, 1.0);
    double next = 0.5 * length;
    while (next > shortest * 1.5)
    {
        const double fraction = next / length;
        const auto folded = std::count_if(folds_at.begin(), folds_at.end(),
                                          [fraction](double s) { return s < fraction; });
        if (Index(comm.sum(std::int64_t(folded))) <= max_cells)
            break;
        next *= 0.5;
    }
    return next;
}

} // namespace

SteppedMorph morph_in_steps(const PolyMesh& mesh, const CompactList& cell_faces,
                            const Constraints& c, const StepSettings& settings,
                            const DeformationMaker& make, bool fit,
                            const std::function<InvalidCells()>& invalid_before,
                            const Decomposition* decomposition, PolyMesh* in_place)
{
    const parallel::Communicator& comm = communicator(decomposition);
    SteppedMorph out;
    if (in_place != nullptr && in_place != &mesh)
        throw std::logic_error("morph_in_steps: in_place must be the mesh itself");
    // One working mesh: its points are the accepted state, or a trial swapped in and out.
    // In place it is the mesh itself, with its own points kept aside; else a copy.
    std::optional<PolyMesh> copy;
    std::optional<Points> aside;
    if (in_place != nullptr)
        aside = mesh.points;
    else
        copy.emplace(mesh);
    PolyMesh& current = in_place != nullptr ? *in_place : *copy;
    const Points& x0 = aside ? *aside : mesh.points; // the unmorphed points
    OriginalState original =
        aside ? OriginalState(current, *aside, cell_faces) : OriginalState(mesh, cell_faces);
    Points other;
    const bool is_auto = settings.steps == 0 && fit;
    const int fixed_steps = (settings.steps > 0 && fit) ? settings.steps : 1;
    const double shortest = 1.0 / settings.max_steps;
    // auto: lengths 1/2^k, exact binary fractions; N steps: k/N from an integer counter.
    double done = 0.0, length = 1.0;
    int steps_done = 0;
    bool stuck = false; // auto: even the shortest step failed; the rest goes in one step
    while (done < 1.0)
    {
        StepRecord record;
        record.from = done;
        if (!is_auto)
            record.to = steps_done + 1 >= fixed_steps ? 1.0 : double(steps_done + 1) / fixed_steps;
        else
            record.to = stuck ? 1.0 : std::min(1.0, done + length);
        const Constraints step = step_constraints(c, x0, current.points, record.to);
        PointMorph m = fit_step(current, step, make, fit, decomposition, record);
        // The check before the morph may still read the mesh: in place, wait for it before
        // the mesh's points change.
        const InvalidCells before = invalid_before();
        add_rows(current.points, m.displacement, 1.0, other);
        std::swap(current.points, other); // current: the trial; other: the accepted state
        MeshGeometry geometry;
        std::vector<char> pyramid_errors;
        const auto choose = [&]
        {
            if (fit && c.jump_smoothing == JumpSmoothingMode::automatic)
                choose_band(current, cell_faces, geometry, other, m, comm, record);
        };
        check_step(current, cell_faces, before, settings, original, comm, record, geometry,
                   pyramid_errors, choose);
        const bool failed = record.invalid.worse_than(before);
        const bool redo = failed && is_auto && !stuck && length > shortest * 1.5;
        record.accepted = !redo;
        out.steps.push_back(record);
        log_step(out.steps.size(), record, failed, redo, is_auto && !stuck);
        if (redo)
        {
            std::swap(current.points, other); // back to the accepted state
            const double next = record.untangle.skipped_cells > 0
                                    ? halved_length(current, cell_faces, m.displacement, length,
                                                    shortest, settings.max_untangle_cells, comm)
                                    : 0.5 * length;
            if (next < 0.5 * length)
                log::info() << "    (its field folds more than maxUntangleCells cells at every "
                               "length down to "
                            << format_fraction(2 * next) << " of the motion: next "
                            << format_fraction(next) << ")";
            length = next;
            continue;
        }
        if (failed && out.valid_fraction == 1.0)
            out.valid_fraction = record.from;
        stuck = stuck || (failed && is_auto);
        out.last = std::move(m);
        out.geometry = std::move(geometry);
        out.pyramid_errors = std::move(pyramid_errors);
        done = record.to;
        ++steps_done;
    }
    add_rows(current.points, x0, -1.0, out.displacement);
    out.points = std::move(current.points);
    if (aside)
        current.points = std::move(*aside); // in place: the mesh as it was given
    return out;
}

} // namespace meshmorph::morph
