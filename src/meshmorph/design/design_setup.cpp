// SPDX-License-Identifier: GPL-3.0-or-later
// -variables: read, check the mesh, one fit and evaluation per variable, streamed to disk.
#include "meshmorph/design/design_setup.h"

#include <algorithm>
#include <optional>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/design/case_fingerprint.h"
#include "meshmorph/design/design_case.h"
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

} // namespace

DesignSetupResult setup_design(const morph::MorphOptions& options)
{
    const Stopwatch clock;
    DesignCase dc = read_design_case(options);
    require_fitted_method(dc.settings);
    const PolyMesh& mesh = dc.foam.mesh;
    morph::PointDisplacementInputs field;
    if (dc.variables.reads_point_displacement())
        field = morph::read_point_displacement(dc.mesh_case, dc.foam, options.region,
                                               parallel::Communicator::world());
    const VariableConstraints constraints(mesh, dc.setup, dc.variables, &field, dc.parts());

    DesignSetupResult result;
    result.method = morph::describe(dc.settings, 0);
    const CompactList cf = cell_faces(mesh);
    result.before =
        morph::check_morph_mesh(mesh, cf, compute_geometry(mesh, cf), {}, dc.decomposition);

    const DesignBasisHeader header = make_header(dc, result.before);
    log::info() << "Setting up " << dc.variables.size() << " design variables (method "
                << header.method << ")";
    const parallel::Communicator& comm = parallel::Communicator::world();
    std::optional<DesignBasisWriter> writer_slot;
    parallel::collective(comm, [&] { writer_slot.emplace(dc.basis_path, header); });
    DesignBasisWriter& writer = *writer_slot;
    for (Index j = 0; j < dc.variables.size(); ++j)
    {
        const DesignVariable& v = dc.variables.variables[std::size_t(j)];
        const bool moves = constraints.moves_anything(j);
        const VariableBlock block =
            moves ? unit_field(dc, constraints.unit(j)) : still_field(header);
        log_variable(v, block, moves, dc.parts());
        parallel::collective(comm, [&] { writer.append(block); });
        result.names.push_back(v.name);
        result.fits.push_back(block.fit);
        result.moves.push_back(moves);
        result.n_constrained = std::max(result.n_constrained, Index(block.constrained.size()));
    }
    if (std::none_of(result.moves.begin(), result.moves.end(), [](char m) { return m != 0; }))
        throw InvalidInput(dc.dict_path.string() + ": no design variable moves any point");
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
