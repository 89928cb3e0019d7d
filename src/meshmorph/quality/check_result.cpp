// SPDX-License-Identifier: GPL-3.0-or-later
// The check result record.
#include "meshmorph/quality/check_result.h"

#include <algorithm>
#include <stdexcept>

namespace meshmorph
{

std::string_view check_name(CheckId id)
{
    static const std::pair<CheckId, std::string_view> names[] = {
        {CheckId::boundary_definition, "boundaryDefinition"},
        {CheckId::empty_patches, "emptyPatches"},
        {CheckId::cell_addressing, "cellAddressing"},
        {CheckId::point_usage, "pointUsage"},
        {CheckId::upper_triangular, "upperTriangular"},
        {CheckId::face_vertices, "faceVertices"},
        {CheckId::cells_zip_up, "cellsZipUp"},
        {CheckId::face_faces, "faceFaces"},
        {CheckId::internal_face_cells, "internalFaceCells"},
        {CheckId::regions, "regions"},
        {CheckId::edge_alignment, "edgeAlignment"},
        {CheckId::wedges, "wedges"},
        {CheckId::closed_boundary, "closedBoundary"},
        {CheckId::closed_cells, "closedCells"},
        {CheckId::face_areas, "faceAreas"},
        {CheckId::cell_volumes, "cellVolumes"},
        {CheckId::face_orthogonality, "faceOrthogonality"},
        {CheckId::face_pyramids, "facePyramids"},
        {CheckId::face_skewness, "faceSkewness"},
        {CheckId::coupled_points, "coupledPoints"},
        {CheckId::face_tets, "faceTets"},
        {CheckId::edge_length, "edgeLength"},
        {CheckId::face_angles, "faceAngles"},
        {CheckId::face_flatness, "faceFlatness"},
        {CheckId::cell_determinant, "cellDeterminant"},
        {CheckId::concave_cells, "concaveCells"},
        {CheckId::face_weight, "faceWeight"},
        {CheckId::volume_ratio, "volumeRatio"},
        {CheckId::mesh_quality, "meshQuality"},
    };
    for (const auto& [check, name] : names)
        if (check == id)
            return name;
    return "?";
}

namespace
{

template <typename T> const T& typed(const CheckResult& result, std::string_view key)
{
    const Statistic* s = result.find(key);
    if (s == nullptr || !std::holds_alternative<T>(s->value))
        throw std::logic_error("check " + std::string(check_name(result.id)) +
                               " has no statistic " + std::string(key) + " of the requested type");
    return std::get<T>(s->value);
}

} // namespace

void CheckResult::add(std::string key, Statistic::Value value, bool in_json)
{
    statistics.push_back({std::move(key), std::move(value), in_json});
}

void CheckResult::add_average(std::string key, double value, double sum, Index count, bool in_json)
{
    statistics.push_back({std::move(key), value, in_json, sum, count});
}

void CheckResult::add_set(std::string name, MeshSet::Kind kind, std::vector<Index> labels,
                          std::string description)
{
    if (labels.empty())
        return;
    sets.push_back({{std::move(name), kind, as_set(std::move(labels))}, std::move(description)});
}

const Statistic* CheckResult::find(std::string_view key) const
{
    for (const Statistic& s : statistics)
        if (s.key == key)
            return &s;
    return nullptr;
}

Index CheckResult::count(std::string_view key) const
{
    return typed<Index>(*this, key);
}
double CheckResult::real(std::string_view key) const
{
    return typed<double>(*this, key);
}
const Vector3& CheckResult::vector(std::string_view key) const
{
    return typed<Vector3>(*this, key);
}
const Statistic::Counts& CheckResult::counts(std::string_view key) const
{
    return typed<Statistic::Counts>(*this, key);
}
const Statistic::Reals& CheckResult::reals(std::string_view key) const
{
    return typed<Statistic::Reals>(*this, key);
}

std::vector<Index> as_set(std::vector<Index> labels)
{
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    return labels;
}

std::vector<Index> flagged(const std::vector<char>& flags)
{
    std::vector<Index> labels;
    for (std::size_t i = 0; i < flags.size(); ++i)
        if (flags[i])
            labels.push_back(static_cast<Index>(i));
    return labels;
}

} // namespace meshmorph
