// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Read a `pointVectorField` such as `0/pointDisplacement` (docs/polymesh-format.md §8):
//! the internal field (one vector per mesh point) and, per mesh patch, the boundary
//! condition with its values in patch-local point order.
//!
//! Patch entries are matched as OpenFOAM's GeometricBoundaryField does: the exact patch
//! name, then a patch-group name (`inGroups`, plus the group implied by wall and constraint
//! types; the entry written last wins), then, for a patch of type `empty` without an entry,
//! `empty`; then regex keys (the one written last first). Anything else is an error.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/io/foam_header.h"

namespace meshmorph::io
{

//! The boundary condition of one patch.
struct PointPatchField
{
    std::string patch; //!< patch name (mesh order)
    std::string type;  //!< fixedValue, calculated, empty, wedge, symmetryPlane, ...
    std::string key;   //!< the boundaryField keyword that matched ("" for the empty default)
    enum class Match
    {
        name,          //!< exact patch name
        group,         //!< patch group
        regex,         //!< regular-expression key
        empty_default, //!< empty patch without entry
    };
    Match matched_by = Match::name;
    //! nPatchPoints x 3 values in patch-local order (patch_points()), for `fixedValue` and
    //! `calculated`; unset for constraint types.
    std::optional<Points> value;
    //! Whether the values were written `uniform` (value has then identical rows).
    bool is_uniform = false;

    //! Whether this patch prescribes its point values (fixedValue / calculated).
    bool is_prescribed() const { return value.has_value(); }
};

//! A pointVectorField read from a file.
struct PointVectorField
{
    std::filesystem::path path; //!< the file read
    FoamHeader header;
    Points internal; //!< nPoints x 3 internalField (uniform expanded)
    bool internal_is_uniform = false;
    std::vector<PointPatchField> patches; //!< one per mesh patch, in mesh order
};

//! \brief Read a pointVectorField (plain or .gz, ASCII or binary) for `mesh`.
//! Supported patch types: `fixedValue` and `calculated` (with `value`), and the constraint
//! types that must match their patch: `empty`, `wedge`, `symmetryPlane`, `symmetry`,
//! `cyclic`, `cyclicAMI`, `processor`.
//! \throw IoError if the file is missing. \throw ParseError naming the file and line for:
//! a wrong class, an internalField whose size is not nPoints, a patch without a matching
//! entry ("Cannot find patchField entry for <patch>"), an unsupported type (naming the patch
//! and type), a constraint patch with another type, a `value` whose size is not the
//! patch's number of points, a missing `value`.
//! \param calculated_without_value accept `calculated` patches without `value` (as OpenFOAM
//! writes a computed point field, e.g. an adjoint solver's sensitivities): their points take
//! the internalField (PointPatchField::value unset).
PointVectorField read_point_vector_field(const std::filesystem::path& path, const PolyMesh& mesh,
                                         bool calculated_without_value = false);

//! \brief Read `<case>/<time>/<name>` (e.g. name "pointDisplacement", time "0").
PointVectorField read_point_vector_field(const std::filesystem::path& case_dir,
                                         const std::string& time, const std::string& name,
                                         const PolyMesh& mesh);

//! \brief The internal field with every prescribed patch's values written onto its points
//! (nPoints x 3), as OpenFOAM's boundary evaluation would, except that a point shared by
//! prescribed patches with different values is reported instead of resolved by
//! evaluation order.
//! \throw InvalidInput naming the two patches and the point on such a conflict (values
//! that are bit-for-bit equal do not conflict).
Points apply_patch_values(const PointVectorField& field, const PolyMesh& mesh);

} // namespace meshmorph::io
