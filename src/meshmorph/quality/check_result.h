// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The result record of one checkMesh check: its numbers, verdict and offending sets.
//!
//! The quality module has three tiers, as OpenFOAM's primitiveMeshTools (per-face and
//! per-cell metric fields) -> primitiveMesh::check* (threshold, offender set, verdict) ->
//! checkGeometry.C (driver and report): metric functions return fields, check functions
//! turn fields into a CheckResult, and the text and JSON reports walk the list of results.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph
{

//! One offending-element set, named as checkMesh names it (nonOrthoFaces, ...).
struct MeshSet
{
    enum class Kind
    {
        face,
        cell,
        point
    };
    std::string name;
    Kind kind = Kind::face;
    std::vector<Index> labels; //!< sorted, distinct
};

//! An offending set as a check reports it.
struct OffenderSet
{
    MeshSet set;
    //! checkMesh's "  <<Writing N <description> to set <name>" (printed with -writeSets);
    //! empty when the check's own text announces the set (regions).
    std::string description;
    //! The set's size over every rank of a -parallel run (-1: set.labels.size()); each rank
    //! writes its own labels.
    Index total = -1;
    Index size() const { return total >= 0 ? total : static_cast<Index>(set.labels.size()); }
};

//! A number a check reports.
struct Statistic
{
    //! Named counts (meshQualityFailures: criterion -> faces), in report order.
    using Counts = std::vector<std::pair<std::string, Index>>;
    //! Named reals (wedgeAngles: patch -> degrees), in report order.
    using Reals = std::vector<std::pair<std::string, double>>;
    using Value = std::variant<Index, double, Vector3, Counts, Reals>;

    std::string key; //!< the JSON key (camelCase)
    Value value;
    bool in_json = true; //!< false: only the text report prints it
    //! An average's parts (its sum and number of values), so that a -parallel run combines
    //! the ranks as checkMesh does: sums and counts reduced, then divided. 0 otherwise.
    double parts_sum = 0;
    Index parts_count = 0;
};

//! The checks, in checkMesh's report order: what joins a check function's result to its
//! report lines (report_text.cpp), so that a misspelt check is a compile error.
enum class CheckId
{
    boundary_definition,
    empty_patches,
    cell_addressing,
    point_usage,
    upper_triangular,
    face_vertices,
    cells_zip_up,
    face_faces,
    internal_face_cells,
    regions,
    edge_alignment,
    wedges,
    closed_boundary,
    closed_cells,
    face_areas,
    cell_volumes,
    face_orthogonality,
    face_pyramids,
    face_skewness,
    coupled_points,
    face_tets,
    edge_length,
    face_angles,
    face_flatness,
    cell_determinant,
    concave_cells,
    face_weight,
    volume_ratio,
    mesh_quality,
};

//! The check's name in messages and tests, e.g. "faceOrthogonality".
std::string_view check_name(CheckId id);

//! What one check found: its numbers, whether it failed, and the offending elements.
struct CheckResult
{
    //! Which check this is.
    CheckId id;
    //! checkMesh's name of the failed check (e.g. "nonOrthogonality"); empty when it passed.
    //! Checks that only warn ("   *" lines) never fail.
    std::string failure;
    std::vector<Statistic> statistics; //!< in report order
    std::vector<OffenderSet> sets;     //!< non-empty sets only, in report order

    explicit CheckResult(CheckId check_id) : id(check_id) {}

    bool failed() const { return !failure.empty(); }
    //! Append a statistic (integers are counts: Index, never int or size_t).
    void add(std::string key, Statistic::Value value, bool in_json = true);
    //! Append an average `value` computed from `sum` over `count` values.
    void add_average(std::string key, double value, double sum, Index count, bool in_json = true);
    //! Append the set of `labels` (sorted and made distinct here) unless it is empty.
    void add_set(std::string name, MeshSet::Kind kind, std::vector<Index> labels,
                 std::string description);

    //! The statistic `key`, or nullptr.
    const Statistic* find(std::string_view key) const;
    //! Typed access to a statistic. \throw std::logic_error if missing or of another type.
    Index count(std::string_view key) const;
    double real(std::string_view key) const;
    const Vector3& vector(std::string_view key) const;
    const Statistic::Counts& counts(std::string_view key) const;
    const Statistic::Reals& reals(std::string_view key) const;
};

//! \brief A container's size as a count statistic.
template <typename Container> Index size_of(const Container& c)
{
    return static_cast<Index>(c.size());
}

//! \brief Sorted, distinct labels.
std::vector<Index> as_set(std::vector<Index> labels);

//! \brief The indices i where flags[i] != 0, ascending.
std::vector<Index> flagged(const std::vector<char>& flags);

} // namespace meshmorph
