// SPDX-License-Identifier: GPL-3.0-or-later
// A case in memory: the stages of morph_case (morph_stages.h) without the writing, run on
// prescriptions from the morphDict or given as values.
#include "meshmorph/app/morph_session.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/deformation_dict.h"
#include "meshmorph/morph/deformation_methods.h"
#include "meshmorph/morph/distributed_case.h"
#include "meshmorph/morph/morph_output.h"
#include "meshmorph/morph/morph_sensitivity.h"
#include "meshmorph/parallel/communicator.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/check_mesh.h"

namespace meshmorph::app
{

namespace fs = std::filesystem;

namespace
{

void require_rows(const Points& values, Index rows, const std::string& what)
{
    if (values.rows() != rows)
        throw InvalidInput(what + ": " + std::to_string(values.rows()) + " rows given, " +
                           std::to_string(rows) + " expected");
    if (!values.allFinite())
        throw InvalidInput(what + ": a value is not finite (NaN or inf)");
}

std::string patch_names(const PolyMesh& mesh)
{
    std::string names;
    for (const Patch& p : mesh.patches)
        names += (names.empty() ? "" : " ") + p.name;
    return names;
}

Index require_patch(const PolyMesh& mesh, const std::string& name)
{
    const Index k = mesh.find_patch(name);
    if (k < 0)
        throw InvalidInput("no patch '" + name + "' in the mesh (patches: " + patch_names(mesh) +
                           ")");
    return k;
}

//! The morphDict entry for a prescribed patch (its key is the exact patch name, which wins
//! over groups, regular expressions and `default`); replaces an entry of the same name.
void set_patch_entry(morph::MorphSetup& setup, const PatchPrescription& p)
{
    auto& b = setup.boundary;
    b.erase(std::remove_if(b.begin(), b.end(),
                           [&](const morph::BoundaryEntry& e)
                           { return !e.is_regex && e.key == p.patch; }),
            b.end());
    morph::BoundaryEntry entry;
    entry.key = p.patch;
    entry.motion.type = p.type;
    entry.motion.vector = p.vector;
    b.push_back(entry);
}

morph::HandleEntry point_set_handle(const PolyMesh& mesh, const PointSetPrescription& s)
{
    const std::string what = "point set '" + s.name + "'";
    require_rows(s.displacements, static_cast<Index>(s.labels.size()), what + " displacements");
    std::vector<Index> sorted = s.labels;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 0; k < sorted.size(); ++k)
    {
        if (sorted[k] < 0 || sorted[k] >= mesh.n_points())
            throw InvalidInput(what + ": point label " + std::to_string(sorted[k]) +
                               " out of range (" + std::to_string(mesh.n_points()) + " points)");
        if (k > 0 && sorted[k] == sorted[k - 1])
            throw InvalidInput(what + ": point label " + std::to_string(sorted[k]) +
                               " is listed twice");
    }
    morph::HandleEntry h;
    h.name = s.name;
    h.selection = morph::HandleEntry::Selection::labels;
    h.labels = s.labels;
    h.label_displacements = s.displacements;
    return h;
}

bool uses_point_displacement(const morph::MorphSetup& setup)
{
    return std::any_of(setup.boundary.begin(), setup.boundary.end(),
                       [](const morph::BoundaryEntry& e)
                       { return e.motion.type == morph::MotionType::point_displacement; });
}

} // namespace

MorphSession::MorphSession(const morph::MorphOptions& options) : options_(options)
{
    if (options.parallel)
        throw InvalidInput("a decomposed case (-parallel) cannot be opened in memory yet: "
                           "reconstructPar, or run morphMesh -parallel");
    case_dir_ = fs::absolute(options.case_dir).lexically_normal();
    if (!fs::is_directory(case_dir_))
        throw IoError("case directory " + case_dir_.string() + " does not exist");
    dict_path_ = morph::morph_dict_path(options, case_dir_);
    in_.case_dir = case_dir_;
    in_.dict_path = dict_path_;
    morph::read_morph_mesh(options, in_, result_);
    cell_faces_ = cell_faces(in_.foam.mesh);
    moved_.emplace(in_.foam.mesh);
}

void MorphSession::set_points(Points points)
{
    require_rows(points, mesh().n_points(), "points");
    moved_->points = std::move(points);
    result_ = morph::MorphResult{};
}

void MorphSession::reset()
{
    moved_->points = initial_points();
    result_ = morph::MorphResult{};
}

const QualityReport& MorphSession::before()
{
    if (!before_)
        before_ =
            morph::check_morph_mesh(mesh(), cell_faces_, compute_geometry(mesh(), cell_faces_),
                                    CheckMeshSettings{}, in_.decomposition);
    return *before_;
}

void MorphSession::run_morph(const morph::MorphOptions& options,
                             const morph::PointDisplacementInputs* given)
{
    morph::MorphResult result;
    result.method = morph::to_string(in_.settings.method);
    result.instance = in_.foam.points_instance;
    result.region = options.region;
    morph::resolve_constraints(options, in_, result, given);
    result.output_instance = morph::morph_output_instance(options, in_);
    morph::BeforeCheck checked(before());
    morph::morph_resolved(options, in_, cell_faces_, checked, result, moved_);
    result_ = std::move(result);
}

Points MorphSession::sensitivity(const Points& dJdx) const
{
    return morph::morph_sensitivity(in_, result_, dJdx);
}

const morph::MorphResult& MorphSession::morph(const std::optional<fs::path>& dict)
{
    morph::MorphOptions options = options_;
    if (dict)
        options.dict = *dict;
    morph::MorphResult ignored;
    morph::read_morph_dict(options, in_, ignored);
    run_morph(options, nullptr);
    return result_;
}

const morph::MorphResult& MorphSession::morph(const Prescriptions& prescriptions)
{
    if (prescriptions.patches.empty() && prescriptions.point_sets.empty())
        throw InvalidInput("no prescriptions given: name patches or point sets to move");
    morph::MorphResult ignored;
    if (fs::exists(dict_path_)) // the options' morphDict, whatever an earlier morph read
        morph::read_morph_dict(options_, in_, ignored);
    else
    {
        const io::FoamDictionary none;
        in_.setup = morph::MorphSetup{};
        in_.setup.dict_path = "(prescriptions)";
        in_.settings = morph::read_deformation_settings(none, options_.method);
        in_.step_settings = morph::read_step_settings(none);
    }
    const bool dict_reads_field = uses_point_displacement(in_.setup);
    std::optional<morph::PointDisplacementInputs> given;
    for (const PatchPrescription& p : prescriptions.patches)
    {
        const Index k = require_patch(mesh(), p.patch);
        if (!p.vector.allFinite())
            throw InvalidInput("patch '" + p.patch + "': a value is not finite (NaN or inf)");
        set_patch_entry(in_.setup, p);
        if (p.type != morph::MotionType::point_displacement)
            continue;
        if (!given)
            given = dict_reads_field
                        ? morph::read_point_displacement(in_.case_dir, in_.foam, options_.region,
                                                         parallel::Communicator::world())
                        : morph::PointDisplacementInputs{
                              Points::Zero(mesh().n_points(), 3),
                              std::vector<std::optional<Points>>(mesh().patches.size())};
        require_rows(p.values, static_cast<Index>(patch_points(mesh(), mesh().patches[k]).size()),
                     "patch '" + p.patch + "' displacements");
        given->patches[std::size_t(k)] = p.values;
    }
    for (const PointSetPrescription& s : prescriptions.point_sets)
        in_.setup.handles.push_back(point_set_handle(mesh(), s));
    run_morph(options_, given ? &*given : nullptr);
    return result_;
}

QualityReport MorphSession::check(const CheckMeshSettings& settings) const
{
    return check_mesh(*moved_, cell_faces_, compute_geometry(*moved_, cell_faces_), settings);
}

bool MorphSession::is_valid() const
{
    const InvalidCells now = count_invalid_cells(*moved_, compute_geometry(*moved_, cell_faces_));
    if (!invalid_before_)
        invalid_before_ = count_invalid_cells(mesh(), compute_geometry(mesh(), cell_faces_));
    return !now.worse_than(*invalid_before_);
}

fs::path MorphSession::write(bool overwrite)
{
    if (result_.refused && !options_.force)
        throw InvalidInput("the last morph was refused (" + result_.refusal +
                           "): nothing written (open the case with force to write anyway)");
    morph::MorphOptions options = options_;
    options.overwrite = overwrite;
    const std::string instance = morph::morph_output_instance(options, in_);
    if (!overwrite)
        morph::warn_if_replacing(in_.mesh_case, instance, options.region);
    return morph::write_morphed_points(options, moved_->points, in_.foam, in_.mesh_case, instance);
}

} // namespace meshmorph::app
