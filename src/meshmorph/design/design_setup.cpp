// SPDX-License-Identifier: GPL-3.0-or-later
// -variables: read, check the mesh, then a fit and a field per variable streamed to disk, or
// one shared fit and the variables' prescriptions.
#include "meshmorph/design/design_setup.h"

#include <algorithm>
#include <optional>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/design/case_fingerprint.h"
#include "meshmorph/design/design_case.h"
#include "meshmorph/design/lattice_box_cut.h"
#include "meshmorph/design/shared_design_fit.h"
#include "meshmorph/design/variable_constraints.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/deformation_methods.h"
#include "meshmorph/morph/distributed_case.h"
#include "meshmorph/morph/morph_steps.h"
#include "meshmorph/morph/point_displacement_input.h"
#include "meshmorph/morph/point_morph.h"
#include "meshmorph/parallel/collective.h"
#include "meshmorph/parallel/communicator.h"

namespace meshmorph::design
{

namespace
{

void require_fitted_method(const morph::DeformationSettings& settings)
{
    if (!morph::needs_fit(settings))
        throw InvalidInput("method ffd moves its control points as the dictionary says and "
                           "fits nothing: for design variables use method rbf (default), idw "
                           "or dmffd, and a designVariables entry of type ffd for a lattice");
}

DesignBasisHeader make_header(const DesignCase& dc, const QualityReport& before)
{
    DesignBasisHeader h;
    h.points_fingerprint = points_fingerprint(dc.foam.mesh.points);
    h.topology_fingerprint = topology_fingerprint(dc.foam.mesh);
    h.dict_fingerprint = dc.dict_fingerprint;
    h.instance = dc.foam.time;
    h.method = morph::to_string(dc.settings.method);
    h.n_points = dc.foam.mesh.n_points();
    for (const DesignVariable& v : dc.variables.variables)
    {
        h.names.push_back(v.name);
        h.bounds.push_back(v.bounds);
    }
    h.negative_volume_cells_before = before.negative_volume_cells;
    h.wrong_pyramids_before = before.incorrectly_oriented_face_pyramids;
    return h;
}

//! One variable's field: fit its unit constraints, evaluate at every point (one step).
VariableBlock unit_field(const DesignCase& dc, const morph::Constraints& c)
{
    const PolyMesh& mesh = dc.foam.mesh;
    const Index n_fit = c.n_prescribed_points + c.n_slip_points;
    const auto deformation = morph::make_deformation(dc.settings, mesh.points, n_fit);
    morph::PointMorph pm = morph::morph_points(mesh, c, *deformation, true, false, dc.parts());
    morph::measure_constraint_error(c, mesh.points, pm, dc.parts());
    VariableBlock block;
    block.fit = {pm.max_constraint_error, pm.relative_constraint_error,
                 double(pm.report.num_centres), pm.fit_seconds + pm.evaluate_seconds};
    block.constrained = c.points;
    block.prescribed = c.displacements;
    block.field = std::move(pm.displacement);
    return block;
}

VariableBlock still_field(const DesignBasisHeader& h)
{
    return {{}, {}, Points::Zero(0, 3), Points::Zero(h.n_points, 3)};
}

void log_shared_variable(const DesignVariable& v, const VariableBlock& b, bool moves)
{
    if (!moves)
    {
        log::info() << "Variable " << v.name
                    << ": its control point moves none of the lattice's patch points (gradient "
                       "zero)";
        return;
    }
    log::info() << "Variable " << v.name << ": max prescribed "
                << format_scalar(morph::max_norm(b.prescribed), 4) << " at " << b.constrained.size()
                << " points";
}

void log_variable(const DesignVariable& v, const VariableBlock& b, bool moves,
                  const morph::Decomposition* parts)
{
    const auto largest = [&](const Points& p)
    {
        const double local = p.rows() > 0 ? p.rowwise().norm().maxCoeff() : 0.0;
        return parts != nullptr ? parts->comm->max(local) : local;
    };
    const double prescribed = largest(b.prescribed), field = largest(b.field);
    if (!moves)
    {
        log::info() << "Variable " << v.name
                    << ": its control point moves none of the lattice's patch points (field "
                       "zero, gradient zero)";
        return;
    }
    log::info() << "Variable " << v.name << ": max prescribed " << format_scalar(prescribed, 4)
                << ", max field " << format_scalar(field, 4) << ", constraint error "
                << format_scalar(b.fit.relative_constraint_error, 3) << " (relative), "
                << Index(b.fit.centres) << " centres, " << format_seconds(b.fit.seconds) << " s";
}

//! What the set-up stores, decided before anything is written.
struct StoragePlan
{
    bool shared = false;
    std::string reason;
    Index first_moving = -1;
    std::vector<char> moves;
    morph::Constraints constraints; //!< shared: the first moving variable's
    std::vector<SparsePrescription> units;
};

//! Why the moving variables cannot share one fit ("" when they can); fills the plan's
//! constraints and units on the way.
std::string gather_shared(const DesignCase& dc, const VariableConstraints& constraints,
                          StoragePlan& plan)
{
    if (dc.parallel) // before any collective: every rank decides alike
        return why_not_shared(morph::Constraints{}, true);
    plan.constraints = constraints.unit(plan.first_moving);
    if (std::string why = why_not_shared(plan.constraints, false); !why.empty())
        return why;
    plan.units.assign(plan.moves.size(), SparsePrescription{});
    for (std::size_t j = 0; j < plan.moves.size(); ++j)
    {
        if (!plan.moves[j])
            continue;
        const morph::Constraints c =
            Index(j) == plan.first_moving ? plan.constraints : constraints.unit(Index(j));
        if (std::string why = why_not_shared(plan.constraints, c); !why.empty())
            return why;
        plan.units[j] = sparse_prescription(c.displacements);
    }
    return "";
}

StoragePlan plan_storage(const DesignCase& dc, const VariableConstraints& constraints)
{
    StoragePlan plan;
    for (Index j = 0; j < dc.variables.size(); ++j)
        plan.moves.push_back(constraints.moves_anything(j));
    const auto moving = std::count(plan.moves.begin(), plan.moves.end(), char(1));
    if (moving == 0)
        throw InvalidInput(dc.dict_path.string() + ": no design variable moves any point");
    plan.first_moving =
        Index(std::find(plan.moves.begin(), plan.moves.end(), char(1)) - plan.moves.begin());
    const std::string counted = std::to_string(moving) + " variables move";
    if (dc.storage == DesignStorage::fields)
    {
        plan.reason = "designBasis fields";
        return plan;
    }
    if (dc.storage == DesignStorage::automatic && moving <= shared_above)
    {
        plan.reason = "auto: " + counted + " (shared above " + std::to_string(shared_above) + ")";
        return plan;
    }
    const std::string why = gather_shared(dc, constraints, plan);
    if (why.empty())
    {
        plan.shared = true;
        plan.reason =
            dc.storage == DesignStorage::shared ? "designBasis shared" : "auto: " + counted;
        return plan;
    }
    if (dc.storage == DesignStorage::shared)
        throw InvalidInput(dc.dict_path.string() + ": designBasis shared is not available for " +
                           why + "; use designBasis fields (or auto)");
    plan.units.clear();
    plan.reason = "auto: " + counted + ", but fields for " + why;
    return plan;
}

//! The fields storage: a fit and a field per variable, streamed to the writer.
void write_fields(const DesignCase& dc, const VariableConstraints& constraints,
                  const StoragePlan& plan, const DesignBasisHeader& header,
                  DesignBasisWriter& writer, DesignSetupResult& result)
{
    const parallel::Communicator& comm = parallel::Communicator::world();
    for (Index j = 0; j < dc.variables.size(); ++j)
    {
        const DesignVariable& v = dc.variables.variables[std::size_t(j)];
        const bool moves = plan.moves[std::size_t(j)] != 0;
        const VariableBlock block =
            moves ? unit_field(dc, constraints.unit(j)) : still_field(header);
        log_variable(v, block, moves, dc.parts());
        parallel::collective(comm, [&] { writer.append(block); });
        result.names.push_back(v.name);
        result.fits.push_back(block.fit);
        result.n_constrained = std::max(result.n_constrained, Index(block.constrained.size()));
    }
}

//! The shared storage: one fit chosen for all, and each variable's prescription.
void write_shared(const DesignCase& dc, StoragePlan& plan, DesignBasisWriter& writer,
                  DesignSetupResult& result)
{
    const std::vector<Index> points = plan.constraints.points;
    const SharedDesignFit fit(dc.foam.mesh, dc.settings, std::move(plan.constraints),
                              std::move(plan.units));
    const VariableFit shared{fit.max_constraint_error(), fit.relative_constraint_error(),
                             double(fit.report().num_centres), fit.choice_seconds()};
    for (std::size_t j = 0; j < dc.variables.variables.size(); ++j)
    {
        const SparsePrescription& unit = fit.units()[j];
        VariableBlock block{shared, {}, unit.values, Points(0, 3)};
        for (const Index r : unit.rows)
            block.constrained.push_back(points[std::size_t(r)]);
        log_shared_variable(dc.variables.variables[j], block, plan.moves[j] != 0);
        writer.append(block);
        result.names.push_back(dc.variables.variables[j].name);
        result.fits.push_back(shared);
    }
    result.n_constrained = Index(points.size());
}

} // namespace

DesignSetupResult setup_design(const morph::MorphOptions& options)
{
    const Stopwatch clock;
    DesignCase dc = read_design_case(options);
    require_fitted_method(dc.settings);
    const PolyMesh& mesh = dc.foam.mesh;
    const morph::PointDisplacementInputs field = read_variable_fields(dc, options);
    const VariableConstraints constraints(mesh, dc.setup, dc.variables, &field, dc.parts());
    warn_lattice_box_cuts(mesh, dc.variables, constraints, parallel::Communicator::world());

    DesignSetupResult result;
    result.method = morph::describe(dc.settings, 0);
    const CompactList cf = cell_faces(mesh);
    result.before =
        morph::check_morph_mesh(mesh, cf, compute_geometry(mesh, cf), {}, dc.decomposition);

    StoragePlan plan = plan_storage(dc, constraints);
    DesignBasisHeader header = make_header(dc, result.before);
    header.shared = plan.shared;
    header.shared_template = plan.shared ? plan.first_moving : -1;
    result.storage = plan.shared ? "shared" : "fields";
    result.storage_reason = plan.reason;
    result.moves = plan.moves;
    log::info() << "Setting up " << dc.variables.size() << " design variables (method "
                << header.method << "; storage " << result.storage << ", " << plan.reason << ")";
    const parallel::Communicator& comm = parallel::Communicator::world();
    std::optional<DesignBasisWriter> writer_slot;
    parallel::collective(comm, [&] { writer_slot.emplace(dc.basis_path, header); });
    DesignBasisWriter& writer = *writer_slot;
    if (plan.shared)
        write_shared(dc, plan, writer, result);
    else
        write_fields(dc, constraints, plan, header, writer, result);
    parallel::collective(comm, [&] { writer.commit(); });
    result.n_constrained = Index(comm.max(std::int64_t(result.n_constrained)));
    result.basis_file = dc.basis_path;
    result.n_points = morph::global_count(dc.decomposition, mesh.n_points(), true);
    std::error_code ec; // a size that cannot be read is reported as 0, never thrown
    const std::uintmax_t bytes = std::filesystem::file_size(dc.basis_path, ec);
    result.bytes = std::uintmax_t(comm.sum(std::int64_t(ec ? 0 : bytes)));
    result.seconds = clock.seconds();
    log::info() << "Wrote design set-up " << dc.basis_path.string() << " ("
                << format_scalar(double(result.bytes) / 1048576.0, 4) << " MB) in "
                << format_seconds(result.seconds) << " s";
    return result;
}

} // namespace meshmorph::design
