// SPDX-License-Identifier: GPL-3.0-or-later
// Variants from a stored set-up: combine the fields, check, judge, write.
#include "meshmorph/design/design_variant.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/design/shared_design_fit.h"
#include "meshmorph/design/variable_constraints.h"
#include "meshmorph/io/case_instance.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/distributed_case.h"
#include "meshmorph/morph/morph_output.h"
#include "meshmorph/morph/point_displacement_input.h"
#include "meshmorph/morph/point_morph.h"
#include "meshmorph/parallel/collective.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/check_mesh.h"

namespace meshmorph::design
{

namespace
{

//! Without -time a design command reads the points its set-up was made on.
morph::MorphOptions at_setup_instance(morph::MorphOptions options, const DesignBasisHeader& h)
{
    if (options.time.mode == io::TimeSelection::Mode::first ||
        options.time.mode == io::TimeSelection::Mode::start)
        options.time = io::TimeSelection::at(h.instance);
    return options;
}

std::string joined(const std::vector<std::string>& words)
{
    std::string list;
    for (const std::string& w : words)
        list += (list.empty() ? "" : " ") + w;
    return list;
}

std::string refusal_text(const InvalidCells& after, const DesignBasisHeader& h)
{
    std::string text = "the variant has ";
    if (after.negative_volume_cells > h.negative_volume_cells_before)
        text += std::to_string(after.negative_volume_cells) + " negative-volume cells (" +
                std::to_string(h.negative_volume_cells_before) + " before)";
    else
        text += std::to_string(after.wrong_pyramids) + " incorrectly oriented face pyramids (" +
                std::to_string(h.wrong_pyramids_before) + " before)";
    return text;
}

//! While it lives, the study's mesh holds the set-up's points x0 (and x0 the mesh's): the
//! shared fit is of the set-up's points, the study's mesh holds the last variant's.
class SetupPointsInMesh
{
public:
    SetupPointsInMesh(Points& mesh_points, Points& x0) : mesh_points_(mesh_points), x0_(x0)
    {
        std::swap(mesh_points_, x0_);
    }
    ~SetupPointsInMesh() { std::swap(mesh_points_, x0_); }
    SetupPointsInMesh(const SetupPointsInMesh&) = delete;
    SetupPointsInMesh& operator=(const SetupPointsInMesh&) = delete;

private:
    Points& mesh_points_;
    Points& x0_;
};

} // namespace

DesignStudy::DesignStudy(const morph::MorphOptions& options) : options_(options)
{
    const Stopwatch clock;
    const parallel::Communicator& comm = parallel::Communicator::world();
    const std::filesystem::path mesh_case = design_mesh_case(options);
    parallel::collective(comm,
                         [&] { reader_.emplace(design_basis_path(mesh_case, options.region)); });
    case_ = read_design_case(at_setup_instance(options, header()));
    parallel::collective(comm, [&] { require_current(case_, header(), basis_file().string()); });
    cell_faces_ = cell_faces(case_.foam.mesh);
    x0_ = case_.foam.mesh.points;
    if (header().shared)
        load_shared_fit();
    reserve_row_buffers();
    // Checked once here, not in the first variant: the topology part of every variant's
    // check (check_variant), and the set-up mesh's own failures, which a variant's are
    // compared with. The mesh holds the set-up's points until the first variant.
    // Its corners and topology are what is reused; its per-cell fields are freed for the
    // variants' own.
    setup_report_ =
        without_cell_fields(check_variant(compute_geometry(case_.foam.mesh, cell_faces_)));
    read_seconds_ = clock.seconds();
    log::info() << "Reusing the design set-up " << basis_file().string() << " (" << names().size()
                << " variables, method " << header().method
                << (shared() ? "): one shared fit" : "): no fit");
}

DesignStudy::~DesignStudy() = default;

void DesignStudy::load_shared_fit()
{
    const PolyMesh& mesh = case_.foam.mesh;
    const morph::PointDisplacementInputs field = read_variable_fields(case_, options_);
    const VariableConstraints constraints(mesh, case_.setup, case_.variables, &field, nullptr);
    morph::Constraints shared = constraints.unit(header().shared_template);
    std::vector<Index> row_of(std::size_t(mesh.n_points()), -1);
    for (std::size_t i = 0; i < shared.points.size(); ++i)
        row_of[std::size_t(shared.points[i])] = Index(i);
    std::vector<SparsePrescription> units(names().size());
    reader_->rewind();
    VariableBlock block;
    for (std::size_t j = 0; j < names().size(); ++j)
    {
        reader_->next(block);
        for (const Index label : block.constrained)
        {
            if (row_of[std::size_t(label)] < 0)
                throw InvalidInput("the design set-up " + basis_file().string() +
                                   " prescribes a point that its constraints do not hold: run "
                                   "morphMesh -variables again");
            units[j].rows.push_back(row_of[std::size_t(label)]);
        }
        units[j].values = block.prescribed;
    }
    shared_ = std::make_unique<SharedDesignFit>(mesh, case_.settings, std::move(shared),
                                                std::move(units));
}

Points DesignStudy::apply_shared(const Points& prescription)
{
    const SetupPointsInMesh at_setup(case_.foam.mesh.points, x0_);
    return shared_->apply(prescription);
}

void DesignStudy::check_amplitudes(const std::vector<double>& a) const
{
    if (a.size() != names().size())
        throw InvalidInput(std::to_string(a.size()) + " amplitudes given, the set-up has " +
                           std::to_string(names().size()) + " design variables (" +
                           joined(names()) + ")");
    for (std::size_t j = 0; j < a.size(); ++j)
    {
        if (!std::isfinite(a[j]))
            throw InvalidInput("the amplitude of " + names()[j] + " is not finite");
        const auto& b = header().bounds[j];
        if (b && (a[j] < b->first || a[j] > b->second))
            throw InvalidInput("the amplitude " + format_scalar(a[j], 6) + " of " + names()[j] +
                               " is outside its bounds (" + format_scalar(b->first, 6) + " " +
                               format_scalar(b->second, 6) + ")");
    }
}

Points DesignStudy::combine(const std::vector<double>& a, ConstraintMisfit* misfit)
{
    Points sum;
    combine_into(a, sum, misfit);
    return sum;
}

namespace
{

//! `misfit` zeroed for n points, its storage kept when it has the size.
void clear_misfit(ConstraintMisfit& misfit, Index n)
{
    misfit.error.setZero(n, 3);
    misfit.constrained.assign(std::size_t(n), 0);
}

} // namespace

void DesignStudy::combine_into(const std::vector<double>& a, Points& sum, ConstraintMisfit* misfit)
{
    const Index n = header().n_points;
    if (misfit != nullptr)
        clear_misfit(*misfit, n);
    if (shared_)
    {
        const Points p = shared_->prescription(a);
        sum = apply_shared(p);
        if (misfit == nullptr)
            return;
        const std::vector<Index>& points = shared_->constraints().points;
        for (std::size_t i = 0; i < points.size(); ++i)
        {
            misfit->error.row(points[i]) = sum.row(points[i]) - p.row(Eigen::Index(i));
            misfit->constrained[std::size_t(points[i])] = 1;
        }
        return;
    }
    sum.setZero(n, 3);
    reader_->rewind();
    VariableBlock& block = row_buffers_.block;
    for (double aj : a)
    {
        if (aj == 0.0)
        {
            reader_->skip();
            continue;
        }
        reader_->next(block);
        sum += aj * block.field;
        if (misfit == nullptr)
            continue;
        for (std::size_t k = 0; k < block.constrained.size(); ++k)
        {
            const Index i = block.constrained[k];
            misfit->error.row(i) += aj * (block.field.row(i) - block.prescribed.row(Index(k)));
            misfit->constrained[std::size_t(i)] = 1;
        }
    }
}

void DesignStudy::reserve_row_buffers()
{
    const Index n = header().n_points;
    row_buffers_.sum.setZero(n, 3);
    clear_misfit(row_buffers_.misfit, n);
    if (!shared_)
        row_buffers_.block.field.setZero(header().field_rows(), 3);
}

std::vector<double> DesignStudy::transpose_product(const Points& g)
{
    if (shared_)
    {
        const SetupPointsInMesh at_setup(case_.foam.mesh.points, x0_);
        return shared_->transpose(g);
    }
    // A point shared by ranks counts once: on the lowest rank holding it.
    const Eigen::VectorXd weight = ownership_weights();
    std::vector<double> out;
    reader_->rewind();
    VariableBlock block;
    for (std::size_t j = 0; j < names().size(); ++j)
    {
        reader_->next(block);
        const double local =
            (weight.array() * (g.array() * block.field.array()).rowwise().sum()).sum();
        out.push_back(case_.parallel ? parallel::Communicator::world().sum(local) : local);
    }
    return out;
}

Eigen::VectorXd DesignStudy::ownership_weights() const
{
    Eigen::VectorXd weight = Eigen::VectorXd::Ones(case_.foam.mesh.n_points());
    if (!case_.parallel)
        return weight;
    const morph::Decomposition& d = case_.decomposition;
    const parallel::Communicator& comm = *d.comm;
    std::vector<Index> shared_global;
    for (Index p : d.shared_points)
        shared_global.push_back(d.global_point[std::size_t(p)]);
    const std::vector<std::vector<Index>> all = comm.gather_values(shared_global);
    std::vector<std::vector<char>> owned_by_rank;
    if (comm.master())
    {
        std::map<Index, int> owner; // global point -> lowest rank holding it
        for (std::size_t r = 0; r < all.size(); ++r)
            for (Index g : all[r])
                owner.try_emplace(g, int(r));
        for (std::size_t r = 0; r < all.size(); ++r)
        {
            std::vector<char> owned;
            for (Index g : all[r])
                owned.push_back(owner.at(g) == int(r));
            owned_by_rank.push_back(std::move(owned));
        }
    }
    const std::vector<char> owned = comm.scatter_values(owned_by_rank);
    for (std::size_t k = 0; k < d.shared_points.size(); ++k)
        weight[d.shared_points[k]] = owned[k] ? 1.0 : 0.0;
    return weight;
}

std::string DesignStudy::next_instance(const std::string& instance) const
{
    return io::next_time_name(io::list_times(case_.mesh_case), instance,
                              io::read_time_settings(case_.case_dir));
}

std::string DesignStudy::back_off(const Points& moved, const std::vector<double>& a, Index invalid)
{
    // The variable whose removal leaves the fewest invalid cells: a variant per variable,
    // which for a shared set-up is a held evaluation each.
    const auto nonzero = std::count_if(a.begin(), a.end(), [](double v) { return v != 0.0; });
    if (shared_ && nonzero > max_back_off_evaluations)
    {
        log::info()
            << "No back-off search: " << nonzero
            << " variables are not zero, and each would cost a variant of the shared set-up";
        return "";
    }
    std::string best;
    Index best_count = invalid;
    PolyMesh& trial = case_.foam.mesh;
    for (std::size_t j = 0; j < a.size(); ++j)
    {
        if (a[j] == 0.0)
            continue;
        std::vector<double> only(a.size(), 0.0);
        only[j] = a[j];
        trial.points = moved - combine(only);
        const InvalidCells c = count_invalid_cells(trial, compute_geometry(trial, cell_faces_));
        Index count = c.negative_volume_cells + c.wrong_pyramids;
        if (case_.parallel)
            count = Index(parallel::Communicator::world().sum(std::int64_t(count)));
        if (count < best_count)
        {
            best_count = count;
            best = names()[j] + " (without it: " + std::to_string(count) + " invalid cells and " +
                   "face pyramids, " + std::to_string(invalid) + " with it)";
        }
    }
    return best;
}

void DesignStudy::measure_misfit(const Points& d, const ConstraintMisfit& misfit,
                                 VariantResult& r) const
{
    double error = 0.0;
    for (Index i = 0; i < d.rows(); ++i)
        if (misfit.constrained[std::size_t(i)])
        {
            error = std::max(error, misfit.error.row(i).norm());
            r.max_prescribed = std::max(r.max_prescribed, (d.row(i) - misfit.error.row(i)).norm());
        }
    r.max_displacement = morph::max_norm(d);
    if (case_.parallel)
    {
        const parallel::Communicator& comm = parallel::Communicator::world();
        error = comm.max(error);
        r.max_prescribed = comm.max(r.max_prescribed);
        r.max_displacement = comm.max(r.max_displacement);
    }
    r.max_constraint_error = error;
    r.relative_constraint_error = r.max_prescribed > 0 ? error / r.max_prescribed : 0.0;
}

bool DesignStudy::has_new_invalid_cells(const InvalidCells& invalid) const
{
    return invalid.worse_than(
        {header().negative_volume_cells_before, header().wrong_pyramids_before});
}

bool DesignStudy::has_new_invalid_cells(const QualityReport& report) const
{
    return has_new_invalid_cells(
        InvalidCells{report.negative_volume_cells, report.incorrectly_oriented_face_pyramids});
}

std::vector<char> DesignStudy::prescribed_points()
{
    std::vector<char> prescribed(std::size_t(header().n_points), 0);
    if (shared_)
    {
        for (const Index i : shared_->constraints().points)
            prescribed[std::size_t(i)] = 1;
        return prescribed;
    }
    reader_->rewind();
    VariableBlock block;
    for (std::size_t j = 0; j < names().size(); ++j)
    {
        reader_->next(block);
        for (Index i : block.constrained)
            prescribed[std::size_t(i)] = 1;
    }
    return prescribed;
}

bool DesignStudy::worth_untangling(VariantResult& r) const
{
    const Index added = r.after.negative_volume_cells - header().negative_volume_cells_before +
                        r.after.incorrectly_oriented_face_pyramids - header().wrong_pyramids_before;
    const Index cells = morph::global_count(case_.decomposition, case_.foam.mesh.n_cells, false);
    if (double(added) <= max_untangled_fraction * double(cells))
        return true;
    r.repair.skipped = "not untangled: " + std::to_string(added) +
                       " new invalid cells and face pyramids, more than " +
                       format_scalar(100.0 * max_untangled_fraction, 3) + "% of the " +
                       std::to_string(cells) + " cells (the local repair is for a few)";
    log::info() << "The variant is " << r.repair.skipped;
    return false;
}

void DesignStudy::repair_variant(VariantResult& r, MeshGeometry& geometry)
{
    if (!repairer_)
        repairer_.emplace(case_.foam.mesh, cell_faces_, x0_, prescribed_points(), case_.parts());
    r.repair = repairer_->repair(case_.foam.mesh, geometry, case_.max_untangle_cells);
    if (!r.repair.tried)
    {
        log::info() << "The variant is " << r.repair.skipped;
        return;
    }
    // Checked as a fresh read of the written points would be.
    geometry = compute_geometry(case_.foam.mesh, cell_faces_);
    r.after = check_variant(geometry);
    r.max_displacement = morph::max_norm(case_.foam.mesh.points - x0_);
    if (case_.parallel)
        r.max_displacement = parallel::Communicator::world().max(r.max_displacement);
    log::info() << "Untangled " << r.repair.invalid_before
                << " invalid cells of the linear combination: moved " << r.repair.points_moved
                << " interior points by at most " << format_scalar(r.repair.max_move, 4) << ", "
                << r.repair.invalid_after << " still invalid (" << format_seconds(r.repair.seconds)
                << " s)";
}

bool DesignStudy::refuse(const std::vector<double>& amplitudes, const MeshGeometry& geometry,
                         VariantResult& r, bool search_back_off)
{
    const InvalidCells invalid{r.after.negative_volume_cells,
                               r.after.incorrectly_oriented_face_pyramids};
    if (!has_new_invalid_cells(r.after))
        return false;
    r.refusal = refusal_text(invalid, header());
    r.invalid_cells_by_patch = morph::invalid_cells_by_patch(
        case_.foam.mesh, cell_faces_, geometry,
        case_.parallel ? *case_.decomposition.comm : parallel::Communicator::world());
    if (!r.invalid_cells_by_patch.empty())
        r.refusal += ", in cells touching " + morph::describe(r.invalid_cells_by_patch);
    if (r.repair.tried)
        r.refusal += " after untangling";
    else if (!r.repair.skipped.empty())
        r.refusal += "; " + r.repair.skipped;
    if (options_.force)
    {
        log::warning() << "-force: writing although " << r.refusal;
        return false;
    }
    r.refused = true;
    if (!search_back_off)
        return true;
    const Points moved = case_.foam.mesh.points;
    r.back_off =
        back_off(moved, amplitudes, invalid.negative_volume_cells + invalid.wrong_pyramids);
    case_.foam.mesh.points = moved;
    return true;
}

VariantResult DesignStudy::evaluate(const std::vector<double>& amplitudes, bool search_back_off)
{
    check_amplitudes(amplitudes);
    VariantResult r;
    r.amplitudes = amplitudes;
    Stopwatch stage;
    Points& d = row_buffers_.sum;
    combine_into(amplitudes, d, &row_buffers_.misfit);
    measure_misfit(d, row_buffers_.misfit, r);
    // The study's mesh carries the variant's points until the next variant (no copy of the
    // topology per design).
    PolyMesh& moved = case_.foam.mesh;
    moved.points = x0_ + d;
    r.combine_seconds = stage.seconds();

    stage.restart();
    MeshGeometry geometry = compute_geometry(moved, cell_faces_);
    r.after = check_variant(geometry);
    if (case_.untangle && has_new_invalid_cells(r.after) && worth_untangling(r))
        repair_variant(r, geometry);
    r.check_seconds = stage.seconds();
    if (!refuse(amplitudes, geometry, r, search_back_off))
        judge_new_check_failures(r);
    return r;
}

void DesignStudy::judge_new_check_failures(VariantResult& r)
{
    // The master holds the whole report in a -parallel run: its verdict is every rank's.
    const parallel::Communicator& comm = parallel::Communicator::world();
    if (comm.broadcast(comm.master() && !r.after.mesh_ok() ? "fails" : "").empty())
        return; // fails nothing: nothing to compare
    const QualityReport& before = *setup_report_;
    std::string refusal;
    if (comm.master())
    {
        r.new_failed_checks = morph::new_failed_checks(before, r.after);
        if (case_.refuse_new_check_failures)
            refusal = morph::new_check_failures_refusal(r.new_failed_checks, "the variant");
    }
    refusal = comm.broadcast(refusal);
    if (refusal.empty())
        return;
    if (options_.force)
    {
        log::warning() << "-force: writing although " << refusal;
        return;
    }
    r.refused = true;
    r.refusal = refusal;
}

void DesignStudy::warn_new_check_failures(const VariantResult& r) const
{
    morph::warn_new_check_failures(r.new_failed_checks, "the variant",
                                   case_.refuse_new_check_failures);
}

QualityReport DesignStudy::check_variant(const MeshGeometry& geometry)
{
    CheckMeshSettings settings;
    settings.cell_fields = false;
    settings.unchanged_topology = setup_report_ ? &*setup_report_ : nullptr;
    return morph::check_morph_mesh(case_.foam.mesh, cell_faces_, geometry, settings,
                                   case_.decomposition);
}

bool DesignStudy::is_valid(const std::vector<double>& amplitudes)
{
    check_amplitudes(amplitudes);
    PolyMesh& moved = case_.foam.mesh;
    combine_into(amplitudes, row_buffers_.sum);
    moved.points = x0_ + row_buffers_.sum;
    InvalidCells now = count_invalid_cells(moved, compute_geometry(moved, cell_faces_));
    const parallel::Communicator& comm = parallel::Communicator::world();
    now.negative_volume_cells =
        static_cast<Index>(comm.sum(std::int64_t(now.negative_volume_cells)));
    now.wrong_pyramids = static_cast<Index>(comm.sum(std::int64_t(now.wrong_pyramids)));
    return !has_new_invalid_cells(now);
}

void DesignStudy::write(VariantResult& r, const std::string& instance)
{
    const Stopwatch stage;
    r.output_instance = instance;
    // Into the mesh's own instance is an overwrite, however it was asked for: the original
    // points are kept as points.orig.
    morph::MorphOptions options = options_;
    options.overwrite = options.overwrite || instance == case_.foam.points_instance;
    parallel::collective(
        parallel::Communicator::world(),
        [&]
        {
            if (!options.overwrite)
                morph::warn_if_replacing(case_.mesh_case, instance, options.region);
            r.points_file = morph::write_morphed_points(options, case_.foam.mesh.points, case_.foam,
                                                        case_.mesh_case, instance);
        });
    r.written = true;
    r.write_seconds = stage.seconds();
}

VariantResult DesignStudy::apply(const std::vector<double>& amplitudes, const std::string& instance)
{
    VariantResult r = evaluate(amplitudes);
    r.output_instance = instance;
    if (!r.refused)
        write(r, instance);
    return r;
}

} // namespace meshmorph::design
