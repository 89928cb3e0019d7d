// SPDX-License-Identifier: GPL-3.0-or-later
// One fit of a space deformation to the constraints and its evaluation at every mesh point.
#include "meshmorph/morph/point_morph.h"

#include "meshmorph/morph/cyclic_coupling.h"
#include "meshmorph/morph/gathered_by_label.h"
#include "meshmorph/morph/jump_smoothing_parallel.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/progress.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/deform/field_io.h"
#include "meshmorph/deform/uniform_grid.h"
#include "meshmorph/parallel/collective.h"

namespace meshmorph::morph
{

namespace
{

//! Rows `indices` of `x`.
Points gather(const Points& x, const std::vector<Index>& indices)
{
    Points out(static_cast<Eigen::Index>(indices.size()), 3);
    for (std::size_t i = 0; i < indices.size(); ++i)
        out.row(static_cast<Eigen::Index>(i)) = x.row(indices[i]);
    return out;
}

//! Positions at which d is evaluated: in 2D cases the projection onto the reference empty
//! plane, so that both planes get the same displacement.
Points evaluation_positions(const Points& x, const Constraints& c)
{
    return c.empty_planes ? c.empty_planes->project(x) : x;
}

void remove_empty_normal(Points& d, const Constraints& c)
{
    if (c.empty_planes)
        c.empty_planes->remove_normal(d);
}

//! A displacement of every mesh point as a 2D or axisymmetric case can follow it: no
//! normal component in 2D, a wedge case's planes moving as rotations of each other.
void keep_planes(Points& d, const Constraints& c)
{
    remove_empty_normal(d, c);
    if (c.wedge)
        c.wedge->apply(d);
}

//! Evaluate in chunks so long evaluations report progress. A chunk of 2^18 points takes
//! about 0.3 s on two cores (the motorBike's 406k points: two chunks); smaller chunks cost
//! more than the progress is worth, since each one sorts its points into blocks anew.
void evaluate_with_progress(const SpaceDeformation& deformation, const Points& x, Points& out,
                            const std::string& task)
{
    out.resize(x.rows(), 3);
    const Eigen::Index chunk = 1 << 18;
    ProgressScope progress(task, x.rows());
    for (Eigen::Index begin = 0; begin < x.rows(); begin += chunk)
    {
        const Eigen::Index n = std::min(chunk, x.rows() - begin);
        deformation.evaluate(x.middleRows(begin, n), out.middleRows(begin, n));
        progress.update(begin + n);
    }
}

//! Whether the morph smooths the band around jumps: asked (`yes` or the default `auto`) and
//! not a wedge case, whose two planes the band's Laplacian would not keep each other's
//! rotation (`yes` is refused there: Constraints' wedge check).
bool smooths_jumps(const Constraints& c)
{
    if (c.wedge && c.jump_smoothing == JumpSmoothingMode::on)
        throw InvalidInput("morphDict 'jumpSmoothing yes;' is not available for a wedge "
                           "(axisymmetric) case: the band's Laplacian would not keep the two "
                           "wedge planes rotations of each other; use 'jumpSmoothing auto;' "
                           "(which leaves wedge cases unsmoothed) or 'no'");
    return c.jump_smoothing != JumpSmoothingMode::off && !c.wedge;
}

//! The jump smoothing's log line.
JumpSmoothing log_jump_smoothing(JumpSmoothing s)
{
    if (s.skipped_reach > 0)
        log::info() << "    jump smoothing skipped: more than " << max_jump_reach_points
                    << " points within " << s.width << " of " << s.jump_constraints
                    << " constraints on jumps (the smoothing is for a band along the jumps, "
                       "not the mesh)";
    if (s.band_points > 0)
        log::info() << "    jump smoothing: " << s.band_points << " points within " << s.width
                    << " of " << s.jump_constraints << " constraints on jumps (Laplacian, "
                    << format_seconds(s.seconds) << " s)";
    return s;
}

//! The handles a deformation is fitted to.
struct FitHandles
{
    Points positions;
    Points values;
    //! Per row given: the handle it was merged into (empty: none merged, row for row).
    std::vector<Eigen::Index> handle_of;
};

//! Row indices of `positions` in lexicographic order (ties by index).
std::vector<Eigen::Index> lexicographic_order(const Points& positions)
{
    std::vector<Eigen::Index> order(static_cast<std::size_t>(positions.rows()));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    std::sort(order.begin(), order.end(),
              [&](Eigen::Index a, Eigen::Index b)
              {
                  for (int k = 0; k < 3; ++k)
                      if (positions(a, k) != positions(b, k))
                          return positions(a, k) < positions(b, k);
                  return a < b;
              });
    return order;
}

//! Handles closer than `same` to each other fitted once: at the position first in
//! lexicographic order, with the mean of their values. In 2D the front and back point of a
//! pair project onto the same position (they differ only by round-off for closed-form
//! motions, by the target's own difference for surfaces and pointDisplacement); meshes with
//! collapsed edges (pitzDaily's merged block corners) add near-duplicate pairs. No solver
//! may see two handles at one position.
FitHandles merge_coincident(const FitHandles& h, double same)
{
    // Cell keys relative to the lower corner stay far below the integer range.
    const Points local = h.positions.rowwise() - h.positions.colwise().minCoeff();
    // Cells much larger than `same`: a position's box nearly always lies in one.
    const meshmorph::detail::UniformGrid grid(local, 1000.0 * same);
    std::vector<Eigen::Index> representative(static_cast<std::size_t>(h.positions.rows()), -1);
    Points sums = Points::Zero(h.values.rows(), 3);
    std::vector<int> counts(static_cast<std::size_t>(h.positions.rows()), 0);
    for (const Eigen::Index a : lexicographic_order(h.positions))
    {
        if (representative[std::size_t(a)] >= 0)
            continue;
        grid.for_each_within(local(a, 0), local(a, 1), local(a, 2), same,
                             [&](Eigen::Index b)
                             {
                                 if (representative[std::size_t(b)] < 0 &&
                                     (h.positions.row(a) - h.positions.row(b)).norm() <= same)
                                     representative[std::size_t(b)] = a;
                             });
    }
    for (Eigen::Index i = 0; i < h.positions.rows(); ++i)
    {
        const Eigen::Index r = representative[std::size_t(i)];
        sums.row(r) += h.values.row(i);
        ++counts[std::size_t(r)];
    }
    const Eigen::Index n = std::count_if(counts.begin(), counts.end(), [](int c) { return c > 0; });
    FitHandles out{Points(n, 3), Points(n, 3), {}};
    std::vector<Eigen::Index> row_of_representative(counts.size(), -1);
    for (Eigen::Index i = 0, k = 0; i < h.positions.rows(); ++i)
        if (counts[std::size_t(i)] > 0)
        {
            out.positions.row(k) = h.positions.row(i);
            out.values.row(k) = sums.row(i) / counts[std::size_t(i)];
            row_of_representative[std::size_t(i)] = k++;
        }
    out.handle_of.resize(counts.size());
    for (std::size_t i = 0; i < counts.size(); ++i)
        out.handle_of[i] = row_of_representative[std::size_t(representative[i])];
    return out;
}

//! The handles to fit: the constrained points at their evaluation positions; in 2D,
//! coincident ones merged.
FitHandles fit_handles(const Points& positions, const Points& prescribed, const Constraints& c)
{
    FitHandles h{positions, prescribed, {}};
    if (!c.empty_planes || positions.rows() < 2)
        return h;
    const double diag =
        (h.positions.colwise().maxCoeff() - h.positions.colwise().minCoeff()).norm();
    if (!(diag > 0.0)) // every handle at one position
        return merge_coincident(h, std::numeric_limits<double>::max());
    // Projection round-off, far below any mesh spacing.
    return merge_coincident(h, 1e-10 * diag);
}

//! What the fit needs: the constrained points (by label: the mesh point, or in a -parallel
//! run its label in the undecomposed mesh), where they are evaluated and their
//! prescriptions, sorted by label; the slip points likewise with their projectors.
struct FitInput
{
    std::vector<Index> labels;
    Points positions, values;
    std::vector<Index> slip_labels;
    Points slip_positions;
    std::vector<Eigen::Matrix3d> slip_projectors;
};

FitInput local_fit_input(const Points& x_eval, const Constraints& c)
{
    return {c.points,      gather(x_eval, c.points),      c.displacements,
            c.slip_points, gather(x_eval, c.slip_points), c.slip_projectors};
}

//! One point as it travels to the master: label, position, value or projector.
struct WirePoint
{
    Index label = 0;
    double position[3] = {0, 0, 0};
    double data[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
};

std::vector<WirePoint> to_wire(const std::vector<Index>& points, const Points& x_eval,
                               const Decomposition& d, const auto& data_of)
{
    std::vector<WirePoint> out(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        out[i].label = d.global_point[std::size_t(points[i])];
        for (int k = 0; k < 3; ++k)
            out[i].position[k] = x_eval(points[i], k);
        data_of(i, out[i].data);
    }
    return out;
}

//! -parallel: the fit input of every rank, on the master (empty elsewhere).
FitInput gathered_fit_input(const Points& x_eval, const Constraints& c, const Decomposition& d)
{
    const auto values = [&](std::size_t i, double* data)
    {
        for (int k = 0; k < 3; ++k)
            data[k] = c.displacements(Eigen::Index(i), k);
    };
    const auto projectors = [&](std::size_t i, double* data)
    { std::copy(c.slip_projectors[i].data(), c.slip_projectors[i].data() + 9, data); };
    const auto fixed = d.comm->gather_values(to_wire(c.points, x_eval, d, values));
    const auto slip = d.comm->gather_values(to_wire(c.slip_points, x_eval, d, projectors));
    FitInput in;
    if (!d.comm->master())
        return in;
    const std::vector<WirePoint> f = sorted_unique(fixed), s = sorted_unique(slip);
    in.positions.resize(Eigen::Index(f.size()), 3);
    in.values.resize(Eigen::Index(f.size()), 3);
    for (std::size_t i = 0; i < f.size(); ++i)
    {
        in.labels.push_back(f[i].label);
        in.positions.row(Eigen::Index(i)) << f[i].position[0], f[i].position[1], f[i].position[2];
        in.values.row(Eigen::Index(i)) << f[i].data[0], f[i].data[1], f[i].data[2];
    }
    in.slip_positions.resize(Eigen::Index(s.size()), 3);
    for (std::size_t i = 0; i < s.size(); ++i)
    {
        in.slip_labels.push_back(s[i].label);
        in.slip_positions.row(Eigen::Index(i)) << s[i].position[0], s[i].position[1],
            s[i].position[2];
        in.slip_projectors.push_back(Eigen::Map<const Eigen::Matrix3d>(s[i].data));
    }
    return in;
}

//! Constrained points (labels) and their prescriptions, sorted by label.
struct Prescription
{
    std::vector<Index> points;
    Points positions;
    Points values;
};

//! The slip points' prescriptions: the tangential part of a first fit without them (zero if
//! nothing else is prescribed).
Points slip_prescriptions(const FitInput& in, const Constraints& c, SpaceDeformation& deformation)
{
    Points slip_values = Points::Zero(static_cast<Eigen::Index>(in.slip_labels.size()), 3);
    if (in.labels.empty())
        return slip_values;
    const FitHandles first = fit_handles(in.positions, in.values, c);
    deformation.fit(first.positions, first.values);
    Points d_slip(slip_values.rows(), 3);
    deformation.evaluate(in.slip_positions, d_slip);
    for (Eigen::Index i = 0; i < d_slip.rows(); ++i)
        slip_values.row(i) =
            (in.slip_projectors[static_cast<std::size_t>(i)] * d_slip.row(i).transpose())
                .transpose();
    remove_empty_normal(slip_values, c);
    return slip_values;
}

//! The constrained and the slip points in one prescription, sorted by label (the handle
//! order does not matter to the fit, but sorted order keeps runs reproducible).
Prescription merged(const FitInput& in, const Points& slip_values)
{
    std::vector<std::tuple<Index, Vector3, Vector3>> all;
    all.reserve(in.labels.size() + in.slip_labels.size());
    for (std::size_t i = 0; i < in.labels.size(); ++i)
        all.emplace_back(in.labels[i], in.positions.row(Eigen::Index(i)).transpose(),
                         in.values.row(Eigen::Index(i)).transpose());
    for (std::size_t i = 0; i < in.slip_labels.size(); ++i)
        all.emplace_back(in.slip_labels[i], in.slip_positions.row(Eigen::Index(i)).transpose(),
                         slip_values.row(Eigen::Index(i)).transpose());
    std::sort(all.begin(), all.end(),
              [](const auto& x, const auto& y) { return std::get<0>(x) < std::get<0>(y); });
    const Eigen::Index n = static_cast<Eigen::Index>(all.size());
    Prescription out{std::vector<Index>(all.size()), Points(n, 3), Points(n, 3)};
    for (std::size_t i = 0; i < all.size(); ++i)
    {
        out.points[i] = std::get<0>(all[i]);
        out.positions.row(Eigen::Index(i)) = std::get<1>(all[i]).transpose();
        out.values.row(Eigen::Index(i)) = std::get<2>(all[i]).transpose();
    }
    return out;
}

//! Fit to the constraints, slip points included (their prescriptions from a first fit).
//! Fitted where the field is evaluated (2D: on the reference empty plane), so an
//! interpolating field meets the constrained points exactly.
Prescription fit_constraints(const FitInput& in, const Constraints& c,
                             SpaceDeformation& deformation)
{
    if (in.labels.empty() && in.slip_labels.empty())
        throw InvalidInput("nothing to fit: no point has a prescribed displacement (every "
                           "patch is free or slip and there are no handles)");
    Prescription p{in.labels, in.positions, in.values};
    if (!in.slip_labels.empty())
        p = merged(in, slip_prescriptions(in, c, deformation));
    const FitHandles handles = fit_handles(p.positions, p.values, c);
    deformation.fit(handles.positions, handles.values);
    return p;
}

//! max over the constrained points of |d - prescribed|.
double max_error(const Points& displacement, const Prescription& p)
{
    double error = 0.0; // a maximum: the same on any number of threads
    const std::int64_t n = std::int64_t(p.points.size());
#pragma omp parallel for schedule(static) reduction(max : error) if (n > 4096)
    for (std::int64_t i = 0; i < n; ++i)
        error =
            std::max(error, (displacement.row(p.points[std::size_t(i)]) - p.values.row(i)).norm());
    return error;
}

double diagonal(const Points& x)
{
    return x.rows() > 0 ? (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm() : 1.0;
}

//! A point shared by ranks gets one displacement: that of the lowest rank holding it. Its
//! ranks evaluate the same field at the same position, but a field's evaluation may depend
//! on the other points evaluated with it (IDW groups nearby queries), so copies could differ
//! in the last bits, and OpenFOAM needs the two sides of a processor face to coincide.
void synchronise_shared_points(const PolyMesh& mesh, const Decomposition& d, Points& displacement)
{
    const std::vector<Index>& shared = d.shared_points;
    const auto data = [&](std::size_t i, double* v)
    {
        for (int k = 0; k < 3; ++k)
            v[k] = displacement(shared[i], k);
    };
    std::vector<WirePoint> mine = to_wire(shared, mesh.points, d, data);
    const std::vector<std::vector<WirePoint>> all = d.comm->gather_values(mine);
    std::vector<std::vector<WirePoint>> back;
    if (d.comm->master())
    {
        const std::vector<WirePoint> first = sorted_unique(all); // stable: lowest rank first
        const auto value_of = [&](Index label)
        {
            return *std::lower_bound(first.begin(), first.end(), label,
                                     [](const WirePoint& w, Index l) { return w.label < l; });
        };
        for (const std::vector<WirePoint>& rank : all)
        {
            back.emplace_back();
            for (const WirePoint& w : rank)
                back.back().push_back(value_of(w.label));
        }
    }
    const std::vector<WirePoint> agreed = d.comm->scatter_values(back);
    for (std::size_t i = 0; i < shared.size(); ++i)
        for (int k = 0; k < 3; ++k)
            displacement(shared[i], k) = agreed[i].data[k];
}

//! -parallel: the master fits (the gathered constraints are those of a serial run, in its
//! order) and sends the field; every rank evaluates it at its own points. The residual is
//! measured on the master at the fit's own points. No snapping (not used in steps).
PointMorph morph_points_distributed(const PolyMesh& mesh, const Constraints& c,
                                    SpaceDeformation& deformation, bool fit, const Decomposition& d)
{
    const parallel::Communicator& comm = *d.comm;
    PointMorph result;
    const Points x_eval = evaluation_positions(mesh.points, c);
    const Stopwatch fit_clock;
    std::unique_ptr<SpaceDeformation> received;
    const SpaceDeformation* field = &deformation;
    std::vector<double> counts(4, 0.0); // constraints, slip points, max prescribed, residual
    Prescription fitted;                // the master's
    if (fit)
    {
        const FitInput in = gathered_fit_input(x_eval, c, d);
        // Each rank gets the field for its own points: an IDW part only as its locally
        // essential tree, not every handle (the pitfall of replicating the boundary).
        const std::vector<std::vector<QueryRegion>> regions =
            comm.gather_values(std::vector<QueryRegion>{query_region(x_eval)});
        std::vector<std::string> per_rank;
        parallel::on_master(comm,
                            [&]
                            {
                                fitted = fit_constraints(in, c, deformation);
                                const Prescription& p = fitted;
                                Points at_handles(p.positions.rows(), 3);
                                deformation.evaluate(p.positions, at_handles);
                                remove_empty_normal(at_handles, c);
                                counts = {double(p.points.size()), double(in.slip_labels.size()),
                                          max_norm(p.values), max_norm(at_handles - p.values)};
                                for (const std::vector<QueryRegion>& r : regions)
                                    per_rank.push_back(write_field(deformation, &r.front()));
                            });
        const std::string bytes = comm.scatter(per_rank);
        counts = comm.broadcast_values(counts);
        // The master too evaluates what it sent itself: every rank alike.
        received = read_field(bytes);
        field = received.get();
    }
    result.report = field->report();
    result.fit_seconds = fit_clock.seconds();
    result.n_constraints = static_cast<Index>(counts[0]);
    result.n_slip = static_cast<Index>(counts[1]);

    const Stopwatch eval_clock;
    evaluate_with_progress(*field, x_eval, result.displacement, "evaluate");
    if (fit && smooths_jumps(c))
        result.jump_smoothing = log_jump_smoothing(smooth_jumps_distributed(
            mesh, x_eval, d, fitted.points, fitted.positions, fitted.values, result.displacement));
    keep_planes(result.displacement, c);
    coupled_mean(c.cyclic_pairs, result.displacement);
    synchronise_shared_points(mesh, d, result.displacement);
    result.evaluate_seconds = eval_clock.seconds();

    const Points corners = bounding_corners(mesh.points, &d);
    result.max_prescribed = counts[2];
    result.max_fit_residual = counts[3];
    result.max_constraint_error = counts[3];
    const double scale =
        std::max(result.max_prescribed, 1e-12 * (corners.row(1) - corners.row(0)).norm());
    result.relative_fit_residual = result.max_fit_residual / scale;
    result.relative_constraint_error = result.max_constraint_error / scale;
    return result;
}

} // namespace

PointMorph morph_points(const PolyMesh& mesh, const Constraints& c, SpaceDeformation& deformation,
                        bool fit, bool snap, const Decomposition* decomposition)
{
    if (decomposition != nullptr && decomposition->is_distributed())
        return morph_points_distributed(mesh, c, deformation, fit, *decomposition);
    PointMorph result;
    const Points x_eval = evaluation_positions(mesh.points, c);
    const Stopwatch fit_clock;
    const Prescription p = fit ? fit_constraints(local_fit_input(x_eval, c), c, deformation)
                               : Prescription{c.points, gather(x_eval, c.points), c.displacements};
    result.n_slip = fit ? static_cast<Index>(c.slip_points.size()) : 0;
    result.report = deformation.report();
    result.fit_seconds = fit_clock.seconds();
    result.n_constraints = static_cast<Index>(p.points.size());

    const Stopwatch eval_clock;
    evaluate_with_progress(deformation, x_eval, result.displacement, "evaluate");
    if (fit && smooths_jumps(c))
        result.jump_smoothing =
            log_jump_smoothing(smooth_jumps(mesh, x_eval, p.points, p.values, result.displacement));
    keep_planes(result.displacement, c);
    coupled_mean(c.cyclic_pairs, result.displacement);
    result.evaluate_seconds = eval_clock.seconds();

    // The fitted field's residual at the constrained points, then the error of the field
    // actually applied (0 after snapping, up to the 2D projection).
    result.max_prescribed = max_norm(p.values);
    result.max_fit_residual = max_error(result.displacement, p);
    const double scale = std::max(result.max_prescribed, 1e-12 * diagonal(mesh.points));
    result.relative_fit_residual = result.max_fit_residual / scale;
    if (snap && fit)
    {
        for (std::size_t i = 0; i < p.points.size(); ++i)
            result.displacement.row(p.points[i]) = p.values.row(static_cast<Eigen::Index>(i));
        keep_planes(result.displacement, c);
        result.snapped = true;
    }
    result.max_constraint_error = max_error(result.displacement, p);
    result.relative_constraint_error = result.max_constraint_error / scale;
    return result;
}

namespace
{

//! Per row given to fit_handles(), its handle's row of `at_handles` (a handle merged from
//! several rows, 2D's front and back points, was fitted at their mean: each gets its share).
Points per_given_row(const FitHandles& handles, const Points& at_handles)
{
    if (handles.handle_of.empty())
        return at_handles;
    std::vector<int> members(std::size_t(at_handles.rows()), 0);
    for (const Eigen::Index h : handles.handle_of)
        ++members[std::size_t(h)];
    Points out(Eigen::Index(handles.handle_of.size()), 3);
    for (std::size_t i = 0; i < handles.handle_of.size(); ++i)
    {
        const Eigen::Index h = handles.handle_of[i];
        out.row(Eigen::Index(i)) = at_handles.row(h) / members[std::size_t(h)];
    }
    return out;
}

//! The transpose of a field fitted to (positions, values) by `make()`'s deformation and
//! evaluated at x: one row per row given.
Points fit_and_transpose(const FieldMaker& make, const Points& positions, const Points& values,
                         const Constraints& c, const Points& x, const Points& g)
{
    const std::unique_ptr<SpaceDeformation> field = make();
    const FitHandles handles = fit_handles(positions, values, c);
    field->fit(handles.positions, handles.values);
    return per_given_row(handles, field->transpose(x, g));
}

//! The transpose of fit_constraints() evaluated at x_eval, for weights g (2D normal
//! removed): one row per constrained point of `in` (its order). With slip points, their
//! prescriptions came from a first fit (slip_prescriptions: the field there, projected onto
//! their planes): their rows of the final fit's transpose go back through it.
Points fitted_transpose(const FitInput& in, const Constraints& c, const FieldMaker& make,
                        const Points& x_eval, const Points& g)
{
    if (in.labels.empty())
        throw InvalidInput("sensitivity: no point has a prescribed displacement");
    if (in.slip_labels.empty())
        return fit_and_transpose(make, in.positions, in.values, c, x_eval, g);
    const std::unique_ptr<SpaceDeformation> first = make();
    const Prescription p = merged(in, slip_prescriptions(in, c, *first));
    const Points at_p = fit_and_transpose(make, p.positions, p.values, c, x_eval, g);
    // The final fit's rows: the constrained points' directly, the slip points' through the
    // first fit (p is sorted by label; in.labels and in.slip_labels are disjoint).
    std::unordered_map<Index, Eigen::Index> constrained, slipping;
    for (std::size_t i = 0; i < in.labels.size(); ++i)
        constrained.emplace(in.labels[i], Eigen::Index(i));
    for (std::size_t i = 0; i < in.slip_labels.size(); ++i)
        slipping.emplace(in.slip_labels[i], Eigen::Index(i));
    Points out = Points::Zero(Eigen::Index(in.labels.size()), 3);
    Points at_slip = Points::Zero(Eigen::Index(in.slip_labels.size()), 3);
    for (std::size_t k = 0; k < p.points.size(); ++k)
    {
        const Eigen::RowVector3d a = at_p.row(Eigen::Index(k));
        if (const auto it = constrained.find(p.points[k]); it != constrained.end())
            out.row(it->second) += a;
        else
            at_slip.row(slipping.at(p.points[k])) = a;
    }
    // slip value = N P_i f1(x_i): N (2D) and P_i transposed.
    remove_empty_normal(at_slip, c);
    for (Eigen::Index i = 0; i < at_slip.rows(); ++i)
        at_slip.row(i) =
            (in.slip_projectors[std::size_t(i)].transpose() * at_slip.row(i).transpose())
                .transpose();
    const FitHandles first_handles = fit_handles(in.positions, in.values, c);
    out += per_given_row(first_handles, first->transpose(in.slip_positions, at_slip));
    return out;
}

//! -parallel: every rank's points and weights go to the master (a shared point once, by its
//! label, as a serial run has it), which fits as morph_points_distributed() does and
//! transposes; each rank gets back the rows of its constrained points and of its shared
//! points (a point constrained on another rank only, where a patch face lies there, gets the
//! same value as there), into `out` (a row per local point).
void distributed_transpose(const Points& x_eval, const Constraints& c, const FieldMaker& make,
                           const Points& g, const Decomposition& d, Points& out)
{
    const parallel::Communicator& comm = *d.comm;
    const FitInput in = gathered_fit_input(x_eval, c, d);
    std::vector<Index> every(std::size_t(x_eval.rows()));
    std::iota(every.begin(), every.end(), Index{0});
    const auto weights_of = [&](std::size_t i, double* data)
    {
        for (int k = 0; k < 3; ++k)
            data[k] = g(Eigen::Index(i), k);
    };
    const auto points = comm.gather_values(to_wire(every, x_eval, d, weights_of));
    std::vector<char> wanted(std::size_t(x_eval.rows()), 0);
    for (const Index p : c.points)
        wanted[std::size_t(p)] = 1;
    for (const Index p : d.shared_points)
        wanted[std::size_t(p)] = 1;
    std::vector<Index> local, mine;
    for (std::size_t p = 0; p < wanted.size(); ++p)
        if (wanted[p])
        {
            local.push_back(Index(p));
            mine.push_back(d.global_point[p]);
        }
    const std::vector<std::vector<Index>> asked = comm.gather_values(mine);
    std::vector<std::vector<WirePoint>> answers;
    parallel::on_master(comm,
                        [&]
                        {
                            const std::vector<WirePoint> all = sorted_unique(points);
                            Points x(Eigen::Index(all.size()), 3), w(Eigen::Index(all.size()), 3);
                            for (std::size_t i = 0; i < all.size(); ++i)
                                for (int k = 0; k < 3; ++k)
                                {
                                    x(Eigen::Index(i), k) = all[i].position[k];
                                    w(Eigen::Index(i), k) = all[i].data[k];
                                }
                            const Points a = fitted_transpose(in, c, make, x, w);
                            for (const std::vector<Index>& labels : asked)
                            {
                                answers.emplace_back();
                                for (const Index label : labels)
                                {
                                    WirePoint answer; // zero: constrained on no rank
                                    answer.label = label;
                                    const auto at =
                                        std::lower_bound(in.labels.begin(), in.labels.end(), label);
                                    if (at != in.labels.end() && *at == label)
                                        for (int k = 0; k < 3; ++k)
                                            answer.data[k] = a(at - in.labels.begin(), k);
                                    answers.back().push_back(answer);
                                }
                            }
                        });
    const std::vector<WirePoint> back = comm.scatter_values(answers);
    for (std::size_t i = 0; i < back.size(); ++i)
        out.row(local[i]) << back[i].data[0], back[i].data[1], back[i].data[2];
}

} // namespace

Points morph_points_transpose(const PolyMesh& mesh, const Constraints& c, const FieldMaker& make,
                              const Points& weights, const Decomposition* decomposition)
{
    if (c.wedge || !c.cyclic_pairs.empty())
        throw InvalidInput("the sensitivity is not available yet for a morph with wedges or "
                           "cyclic patches");
    const bool smoothed = c.jump_smoothing == JumpSmoothingMode::on;
    if (smoothed &&
        (!c.slip_points.empty() || (decomposition != nullptr && decomposition->is_distributed())))
        throw InvalidInput("the sensitivity is not available yet for a morph whose jump smoothing "
                           "was kept together with slip patches or -parallel: set "
                           "'jumpSmoothing no;' in the morphDict");
    if (weights.rows() != mesh.n_points())
        throw InvalidInput("sensitivity: " + std::to_string(weights.rows()) +
                           " rows of dJ/dx for a mesh of " + std::to_string(mesh.n_points()) +
                           " points");
    const Points x_eval = evaluation_positions(mesh.points, c);
    // d = P f(x_eval) with P the 2D projection (symmetric: its own transpose).
    Points g = weights;
    remove_empty_normal(g, c);
    Points out = Points::Zero(mesh.n_points(), 3);
    if (decomposition != nullptr && decomposition->is_distributed())
    {
        distributed_transpose(x_eval, c, make, g, *decomposition, out);
        return out;
    }
    const FitInput in = local_fit_input(x_eval, c);
    if (smoothed) // d = S f: dJ/df = S^T dJ/dd, the band's rows carried to its border
        smooth_jumps_transpose(mesh, x_eval, in.labels, in.values, g);
    const Points at_constraints = fitted_transpose(in, c, make, x_eval, g);
    for (std::size_t i = 0; i < c.points.size(); ++i)
        out.row(c.points[i]) = at_constraints.row(Eigen::Index(i));
    return out;
}

double max_norm(const Points& values)
{
    double largest = 0.0; // a maximum: the same on any number of threads
    const std::int64_t n = values.rows();
#pragma omp parallel for schedule(static) reduction(max : largest) if (n > 4096)
    for (std::int64_t i = 0; i < n; ++i)
        largest = std::max(largest, values.row(i).norm());
    return largest;
}

} // namespace meshmorph::morph
