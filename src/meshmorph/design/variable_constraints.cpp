// SPDX-License-Identifier: GPL-3.0-or-later
// Unit constraint sets: the base entries frozen, one variable's motion on its patches or
// handle, rotations linearised.
#include "meshmorph/design/variable_constraints.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/morph/constraints.h"
#include "meshmorph/morph/patch_assignment.h"

namespace meshmorph::design
{

using morph::MotionType;

namespace
{

bool keeps_still(MotionType t)
{
    return t == MotionType::fixed || t == MotionType::slip || t == MotionType::free;
}

//! The boundary entries may fix, slip or free patches; a motion there is not a variable.
void require_still_boundary(const morph::MorphSetup& base)
{
    for (const morph::BoundaryEntry& e : base.boundary)
        if (!keeps_still(e.motion.type))
            throw ParseError(base.dict_path, e.line,
                             "boundary entry " + e.key + " has type " +
                                 morph::to_string(e.motion.type) +
                                 ": with designVariables the boundary entries only say what "
                                 "stays fixed, slips or is free; make this motion a design "
                                 "variable (or remove designVariables for a one-off morph)");
}

bool uses_handle(const DesignVariables& vars, const std::string& name)
{
    for (const DesignVariable& v : vars.variables)
        if (v.kind == DesignVariable::Kind::handle && v.handle == name)
            return true;
    return false;
}

//! Handles that no variable moves must not move; every handle starts at zero.
void freeze_handles(const DesignVariables& vars, morph::MorphSetup& base)
{
    for (morph::HandleEntry& h : base.handles)
    {
        if (!uses_handle(vars, h.name) && h.displacement.norm() != 0.0)
            throw ParseError(base.dict_path, h.line,
                             "handle " + h.name +
                                 " moves, but no design variable names it: with "
                                 "designVariables a handle moves only as a variable "
                                 "(handle " +
                                 h.name + "; vector (...);), set its displacement to (0 0 0)");
        h.displacement.setZero();
    }
    for (const DesignVariable& v : vars.variables)
    {
        if (v.kind != DesignVariable::Kind::handle)
            continue;
        bool found = false;
        for (const morph::HandleEntry& h : base.handles)
            found = found || h.name == v.handle;
        if (!found)
            throw ParseError(vars.dict_path, v.line,
                             "design variable " + v.name + ": no handle '" + v.handle +
                                 "' in the handles dictionary");
    }
}

//! The patch keys of a variable or lattice as boundary entries, resolved by OpenFOAM's rules.
std::vector<char> patches_of(const PolyMesh& mesh, const std::string& dict_path,
                             const std::vector<std::string>& keys,
                             const std::vector<bool>& is_regex, std::size_t line, bool decomposed)
{
    morph::MorphSetup only;
    only.dict_path = dict_path;
    for (std::size_t k = 0; k < keys.size(); ++k)
        only.boundary.push_back({keys[k], bool(is_regex[k]), morph::Motion{}, line});
    const std::vector<morph::PatchAssignment> a = morph::assign_patches(mesh, only, decomposed);
    std::vector<char> moved(a.size(), 0);
    for (std::size_t p = 0; p < a.size(); ++p)
        moved[p] = a[p].entry >= 0;
    return moved;
}

//! The unit displacement of a rotation: theta * axis x (x - origin), theta in radians.
Vector3 linear_rotation(const morph::Motion& m, const Vector3& x)
{
    return m.angle_degrees * std::numbers::pi / 180.0 * m.axis.normalized().cross(x - m.origin);
}

//! A handle variable's unit motion on its handle: a vector, or per point (rotations
//! linearised; a scaling is linear already).
void set_unit_motion(const morph::Motion& motion, morph::HandleEntry& h)
{
    if (motion.type == MotionType::translate)
        h.displacement = motion.vector;
    else if (motion.type == MotionType::rotate)
        h.displacement_at = [motion](const Vector3& x) { return linear_rotation(motion, x); };
    else
        h.displacement_at = [motion](const Vector3& x) { return motion.displacement(x); };
}

//! Patch assignment `a` with another motion, its reason and its boundary entry.
morph::PatchAssignment reassigned(const morph::PatchAssignment& a, MotionType motion,
                                  const std::string& matched_by, Index entry)
{
    return {a.patch, a.patch_type, motion, matched_by, entry, a.n_points};
}

//! Rotations of the unit set replaced by their linearisation theta * axis x (x - origin), so
//! that amplitude a moves every point by a times its unit displacement.
void linearise_rotations(const PolyMesh& mesh, morph::Constraints& c)
{
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
        const Index r = c.rotation_of[i];
        if (r < 0)
            continue;
        const morph::Motion& m = c.rotations[std::size_t(r)];
        Vector3 x = mesh.points.row(c.points[i]).transpose();
        if (c.empty_planes)
            x = c.empty_planes->project(x);
        Vector3 d = linear_rotation(m, x);
        if (c.empty_planes)
            d = c.empty_planes->in_plane(d);
        c.displacements.row(Eigen::Index(i)) = d.transpose();
        c.rotation_of[i] = -1;
    }
}

} // namespace

VariableConstraints::VariableConstraints(const PolyMesh& mesh, const morph::MorphSetup& base,
                                         const DesignVariables& variables,
                                         const morph::PointDisplacementInputs* point_displacement,
                                         const morph::Decomposition* decomposition)
    : mesh_(mesh), base_(base), variables_(variables), point_displacement_(point_displacement),
      decomposition_(decomposition)
{
    const bool decomposed = decomposition_ != nullptr;
    require_still_boundary(base_);
    freeze_handles(variables_, base_);
    frozen_ = morph::assign_patches(mesh_, base_, decomposed);
    for (const DesignVariable& v : variables_.variables)
    {
        std::vector<char> moved(mesh_.patches.size(), 0);
        if (v.kind == DesignVariable::Kind::patches)
            moved = patches_of(mesh_, variables_.dict_path, v.patch_keys, v.key_is_regex, v.line,
                               decomposed);
        else if (v.kind == DesignVariable::Kind::lattice_point)
        {
            const DesignLattice& l = variables_.lattices[v.lattice];
            moved = patches_of(mesh_, variables_.dict_path, l.patch_keys, l.key_is_regex, l.line,
                               decomposed);
        }
        for (std::size_t p = 0; p < moved.size(); ++p)
            if (moved[p])
                frozen_[p] = reassigned(frozen_[p], MotionType::fixed, "design variables", -1);
        moved_patches_.push_back(std::move(moved));
    }
}

namespace
{

//! A control point's key as written: (i, j, k), 0 on an axis written with count 1 (its
//! four control points move together, DesignLattice::belongs).
std::array<int, 3> written_key(const DesignLattice& design, Index p)
{
    const std::array<int, 3>& n = design.lattice.counts();
    const std::array<int, 3> at{int(p % n[0]), int((p / n[0]) % n[1]), int(p / (n[0] * n[1]))};
    std::array<int, 3> key{0, 0, 0};
    for (std::size_t a = 0; a < 3; ++a)
        key[a] = design.counts[a] > 1 ? at[a] : 0;
    return key;
}

std::array<int, 3> written_key(const DesignLattice& design, const std::array<int, 3>& ijk)
{
    std::array<int, 3> key = ijk;
    for (std::size_t a = 0; a < 3; ++a)
        if (design.counts[a] <= 1)
            key[a] = 0;
    return key;
}

} // namespace

const VariableConstraints::PointWeights& VariableConstraints::control_weights(Index j) const
{
    const DesignVariable& v = variables_.variables[std::size_t(j)];
    const DesignLattice& design = variables_.lattices[v.lattice];
    lattice_weights_.resize(variables_.lattices.size());
    auto& by_key = lattice_weights_[v.lattice];
    if (by_key.empty())
    {
        // The lattice's variables share its patches: those of this one.
        std::vector<Index> points = points_moved_by(j);
        std::sort(points.begin(), points.end());
        points.erase(std::unique(points.begin(), points.end()), points.end());
        for (const Index i : points)
        {
            Index index[64];
            double weight[64];
            const int n = design.lattice.basis(mesh_.points.row(i).transpose(), FfdOutside::zero,
                                               index, weight);
            std::map<std::array<int, 3>, double> at_point; // summed in basis order
            for (int k = 0; k < n; ++k)
                at_point[written_key(design, index[k])] += weight[k];
            for (const auto& [key, w] : at_point)
                by_key[key].emplace_back(i, w);
        }
        by_key.try_emplace({-1, -1, -1}); // computed, even if no point is in any support
    }
    static const PointWeights none;
    const auto it = by_key.find(written_key(design, v.control_point));
    return it != by_key.end() ? it->second : none;
}

std::vector<Index> VariableConstraints::points_moved_by(Index j) const
{
    std::vector<Index> points;
    for (std::size_t p = 0; p < mesh_.patches.size(); ++p)
        if (moved_patches_[std::size_t(j)][p])
        {
            const std::vector<Index> on_patch = patch_points(mesh_, mesh_.patches[p]);
            points.insert(points.end(), on_patch.begin(), on_patch.end());
        }
    return points;
}

Points VariableConstraints::lattice_field(Index j) const
{
    // Only the points of the lattice's patches take the field's values (claims.h).
    const DesignVariable& v = variables_.variables[std::size_t(j)];
    Points field = Points::Zero(mesh_.n_points(), 3);
    for (const auto& [i, w] : control_weights(j))
        field(i, v.direction) = w;
    return field;
}

bool VariableConstraints::moves_anything(Index j) const
{
    const bool local = moves_any_local_point(j);
    return decomposition_ != nullptr ? decomposition_->comm->any(local) : local;
}

bool VariableConstraints::moves_any_local_point(Index j) const
{
    const DesignVariable& v = variables_.variables[std::size_t(j)];
    if (v.kind != DesignVariable::Kind::lattice_point)
        return true;
    const PointWeights& weights = control_weights(j);
    return std::any_of(weights.begin(), weights.end(),
                       [](const std::pair<Index, double>& w) { return w.second != 0.0; });
}

morph::Constraints VariableConstraints::unit(Index j) const
{
    const DesignVariable& v = variables_.variables[std::size_t(j)];
    morph::MorphSetup setup = base_;
    std::vector<morph::PatchAssignment> assignment = frozen_;
    morph::ConstraintInputs inputs;
    inputs.patches = &assignment;
    inputs.decomposition = decomposition_;
    Points lattice_values;
    // The handles other variables move are left out (their points follow this variable's
    // field, so that variables add up); this variable's handle moves by its vector.
    std::erase_if(setup.handles,
                  [&](const morph::HandleEntry& h)
                  {
                      return uses_handle(variables_, h.name) &&
                             !(v.kind == DesignVariable::Kind::handle && v.handle == h.name);
                  });
    if (v.kind == DesignVariable::Kind::handle)
    {
        for (morph::HandleEntry& h : setup.handles)
            if (h.name == v.handle)
                set_unit_motion(v.motion, h);
    }
    else
    {
        morph::Motion motion = v.motion;
        if (v.kind == DesignVariable::Kind::lattice_point)
        {
            motion.type = MotionType::point_displacement;
            lattice_values = lattice_field(j);
            inputs.point_displacement = &lattice_values;
        }
        else if (motion.type == MotionType::point_displacement)
        {
            inputs.point_displacement = &point_displacement_->internal;
            inputs.patch_point_displacement = &point_displacement_->patches;
        }
        setup.boundary.push_back({v.name, false, motion, v.line});
        const Index entry = Index(setup.boundary.size()) - 1;
        for (std::size_t p = 0; p < assignment.size(); ++p)
            if (moved_patches_[std::size_t(j)][p])
                assignment[p] =
                    reassigned(assignment[p], motion.type, "design variable " + v.name, entry);
    }
    morph::Constraints c;
    try
    {
        c = morph::build_constraints(mesh_, setup, inputs);
    }
    catch (const InvalidInput& e)
    {
        throw InvalidInput("design variable " + v.name + ": " + e.what());
    }
    linearise_rotations(mesh_, c);
    return c;
}

} // namespace meshmorph::design
