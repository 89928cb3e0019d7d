// SPDX-License-Identifier: GPL-3.0-or-later
//! \file morphDict boundary and handle prescriptions, turned into point constraints.
//!
//! The set-up is plain data (MorphSetup), filled from `system/morphDict` by
//! read_morph_setup() or directly by tests. build_constraints() resolves
//! which prescription applies to each boundary patch, evaluates the prescribed
//! displacement of every boundary and handle point, detects and resolves conflicts, and
//! returns the constraint set that the deformation is fitted to.
//!
//! Rules (documented for users in tutorials/README.md and `morphMesh -help`):
//! - Patch matching follows OpenFOAM's pointDisplacement rules: exact patch name first, then
//!   a patch-group name (`inGroups`), then a regex key (the last one written wins), then the
//!   `default` entry (fixed if absent). A literal key that names no patch or group, and a
//!   regex that matches no patch, are errors.
//! - `empty` patches keep OpenFOAM's meaning: the case stays 2D (no displacement normal to
//!   the empty planes, both planes move identically). `wedge` patches slide within their
//!   planes. Neither may be given another type. `processor` patches are an error.
//! - A point on several patches whose prescriptions disagree is a conflict. The `conflicts`
//!   rule decides (default `fixed`: the point does not move, because a domain wall that
//!   touches a moving body — the motorBike tyres on the ground — must stay where it is);
//!   the count is always reported. `first`/`last` pick the entry written first/last in
//!   `boundary`; `average` takes the mean of the prescribed displacements; `error` refuses.
//! - Handles override boundary prescriptions (they are the explicit, local request); the
//!   number of overridden boundary points is reported. Overlapping handles with different
//!   displacements are conflicts under the same rule.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/core/types.h"

namespace meshmorph::io
{
class FoamDictionary;
}

namespace meshmorph::app
{

//! How a boundary patch moves (the `type` of a morphDict boundary entry).
enum class MotionType
{
    fixed,              //!< d = 0
    translate,          //!< d = vector
    rotate,             //!< rigid rotation by angle (degrees) about axis through origin
    scale,              //!< x' = origin + factor (x - origin), componentwise
    point_displacement, //!< d from <time>/pointDisplacement
    surface,            //!< d = closest point on a target surface - x
    slip,               //!< slides within its (planar) patch: tangential part of the fitted d
    free,               //!< unconstrained
};

//! Spelling of a MotionType in morphDict (`pointDisplacement`, ...).
std::string to_string(MotionType type);
//! \throw InvalidInput for an unknown spelling (message lists the valid ones).
MotionType motion_type_from_string(const std::string& word);

//! One prescription, with the parameters its type needs.
struct Motion
{
    MotionType type = MotionType::fixed;
    Vector3 vector = Vector3::Zero(); //!< translate
    Vector3 origin = Vector3::Zero(); //!< rotate, scale
    Vector3 axis = Vector3::UnitZ();  //!< rotate (need not be unit)
    double angle_degrees = 0.0;       //!< rotate
    Vector3 factor = Vector3::Ones(); //!< scale
    std::string file;                 //!< surface: path as written (relative to the case)

    //! Prescribed displacement at x for the closed-form types (fixed, translate, rotate,
    //! scale). \pre type is one of those.
    Vector3 displacement(const Vector3& x) const;
};

//! One entry of the `boundary` sub-dictionary.
struct BoundaryEntry
{
    std::string key;       //!< patch name, group name or regex as written
    bool is_regex = false; //!< key was quoted (OpenFOAM: a quoted key is a regex)
    Motion motion;
    std::size_t line = 0; //!< line in the dictionary (0 if unknown), for messages
};

//! How points selected by several disagreeing prescriptions are resolved.
enum class ConflictRule
{
    error,   //!< refuse with a message naming the points' patches
    first,   //!< the entry written first in `boundary` wins
    last,    //!< the entry written last wins
    fixed,   //!< the point does not move (default)
    average, //!< mean of the prescribed displacements
};

std::string to_string(ConflictRule rule);
//! \throw InvalidInput for an unknown spelling.
ConflictRule conflict_rule_from_string(const std::string& word);

//! One entry of the optional `handles` sub-dictionary (the paper's handle interface).
struct HandleEntry
{
    enum class Selection
    {
        point_zone, //!< the points of a pointZone
        box,        //!< every mesh point inside an axis-aligned box (inclusive)
        points,     //!< the mesh point nearest to each listed position
    };
    std::string name;
    Selection selection = Selection::box;
    std::string zone;                  //!< point_zone
    Vector3 box_min = Vector3::Zero(); //!< box
    Vector3 box_max = Vector3::Zero(); //!< box
    Points points;                     //!< points: k x 3 positions
    Vector3 displacement = Vector3::Zero();
    std::size_t line = 0;
};

//! The morphDict contents that decide the constraints (deformation settings live in
//! deformation_factory.h).
struct MorphSetup
{
    std::string dict_path = "system/morphDict"; //!< for messages
    //! In dictionary order; the literal key `default` is the entry for unlisted patches
    //! (fixed if absent). Order matters for the conflict rules `first` and `last`.
    std::vector<BoundaryEntry> boundary;
    std::vector<HandleEntry> handles;
    ConflictRule conflicts = ConflictRule::fixed;
};

//! \brief Read `conflicts`, `boundary` and `handles` of a parsed morphDict.
//! Every entry is checked: an unknown top-level keyword, an entry that is not a
//! sub-dictionary, an unknown `type`, a missing or extra parameter keyword, a bad value, a
//! handle with zero or several selections. \throw ParseError naming the file, line and entry.
MorphSetup read_morph_setup(const io::FoamDictionary& dict);

//! The prescription chosen for one patch, and why.
struct PatchAssignment
{
    std::string patch;
    std::string patch_type; //!< the patch's own type (wall, empty, ...)
    MotionType motion = MotionType::fixed;
    std::string matched_by; //!< "name", "group <g>", "regex \"...\"", "default", "empty", "wedge"
    Index entry = -1;       //!< index into MorphSetup::boundary; -1 when implicit
    Index n_points = 0;
};

//! Decide the prescription of every patch (see the file comment for the matching order).
//! \throw ParseError (dict path + entry line) for a key matching nothing, a constraint patch
//! (empty/wedge) given another type; InvalidInput for processor patches.
std::vector<PatchAssignment> assign_patches(const PolyMesh& mesh, const MorphSetup& setup);

//! What build_constraints needs besides the mesh: values of the data-driven types.
struct ConstraintInputs
{
    //! nPoints x 3 `pointDisplacement` values (internalField with the patch values applied);
    //! required if any patch uses type pointDisplacement.
    const Points* point_displacement = nullptr;
    //! Optional per-patch values (one entry per mesh patch, nPatchPoints x 3 in patch-local
    //! order, e.g. a fixedValue boundary entry of the field); where set they replace
    //! point_displacement on that patch. Disagreements between patches are conflicts.
    const std::vector<std::optional<Points>>* patch_point_displacement = nullptr;
    //! Closest points on the target surface `file` for each row of `query` (k x 3);
    //! required if any patch uses type surface. May throw IoError/ParseError.
    std::function<Points(const std::string& file, const Points& query)> project_to_surface;
    //! assign_patches(mesh, setup) if the caller already computed it (else it is computed).
    const std::vector<PatchAssignment>* patches = nullptr;
};

//! The resolved constraint set.
struct Constraints
{
    //! Points with a prescribed displacement (sorted mesh point indices) and their values
    //! (already without the component normal to the empty planes in 2D cases).
    std::vector<Index> points;
    Points displacements;
    //! Per entry of points: index into rotations when a rotate entry prescribes it (-1 for
    //! every other prescription), so that a morph in steps turns such points along their arc.
    std::vector<Index> rotation_of;
    std::vector<Motion> rotations;
    //! Points that slide: their displacement is P d(x) with the projector P (removes the
    //! normals of the slip/wedge planes they lie on), decided after a first fit.
    std::vector<Index> slip_points;
    std::vector<Eigen::Matrix3d> slip_projectors;
    //! 2D cases: unit normal of the empty planes and the offset (n.x) of one of them.
    std::optional<Vector3> empty_normal;
    double empty_offset = 0.0;

    std::vector<PatchAssignment> patches;
    Index n_free_points = 0; //!< boundary points left unconstrained (type free)
    Index n_handle_points = 0;
    Index n_handle_overrides = 0; //!< boundary points whose prescription a handle replaced
    Index n_conflicts = 0;        //!< points with disagreeing prescriptions
    //! Points whose prescriptions differ by at most 10% of their shortest boundary edge
    //! (snapped patch edges), not counted or warned about as conflicts: a value off a slip
    //! plane by that little is projected into it, differing values go by the rule.
    Index n_near_agreements = 0;
    double max_near_agreement = 0.0; //!< their largest difference / shortest edge
    ConflictRule conflict_rule = ConflictRule::fixed;
    //! Patch pairs involved in conflicts, e.g. "frontWheel/lowerWall: 120 points".
    std::vector<std::string> conflict_summary;
};

//! Resolve boundary and handle prescriptions into point constraints.
//! \throw ParseError/InvalidInput on dictionary errors (unknown patch/zone, conflicts under
//! rule `error`, non-planar slip patch, missing inputs for data-driven types).
Constraints build_constraints(const PolyMesh& mesh, const MorphSetup& setup,
                              const ConstraintInputs& inputs = {});

//! Unit normal of a planar patch and its offset n.x, or nullopt if the patch is not
//! planar within `tolerance` x its bounding-box diagonal (or has no faces).
std::optional<std::pair<Vector3, double>> patch_plane(const PolyMesh& mesh, const Patch& patch,
                                                      double tolerance = 1e-6);

} // namespace meshmorph::app
