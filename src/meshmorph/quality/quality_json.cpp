// SPDX-License-Identifier: GPL-3.0-or-later
// JSON form of a QualityReport (the mesh statistics, then every check result's statistics)
// and the before/after summary table.
#include "meshmorph/quality/quality_json.h"

#include <cmath>
#include <ostream>

namespace meshmorph
{

namespace
{

nlohmann::json number(double v)
{
    if (!std::isfinite(v))
        return nullptr;
    return v;
}

std::string pad(const std::string& text, std::size_t width)
{
    return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

nlohmann::json statistic_json(const Statistic::Value& value)
{
    if (const Index* count = std::get_if<Index>(&value))
        return *count;
    if (const double* real = std::get_if<double>(&value))
        return number(*real);
    if (const Vector3* v = std::get_if<Vector3>(&value))
        return {v->x(), v->y(), v->z()};
    nlohmann::json named = nlohmann::json::object();
    if (const Statistic::Reals* reals = std::get_if<Statistic::Reals>(&value))
        for (const auto& [key, real] : *reals)
            named[key] = number(real);
    else
        for (const auto& [key, count] : std::get<Statistic::Counts>(value))
            named[key] = count;
    return named;
}

} // namespace

nlohmann::json quality_json(const QualityReport& r)
{
    nlohmann::json j;
    j["points"] = r.n_points;
    j["faces"] = r.n_faces;
    j["internalFaces"] = r.n_internal_faces;
    j["cells"] = r.n_cells;
    j["patches"] = r.n_patches;
    j["cellTypes"] = {{"hexahedra", r.cell_types.hex},       {"prisms", r.cell_types.prism},
                      {"wedges", r.cell_types.wedge},        {"pyramids", r.cell_types.pyramid},
                      {"tetWedges", r.cell_types.tet_wedge}, {"tetrahedra", r.cell_types.tet},
                      {"polyhedra", r.cell_types.polyhedron}};
    j["boundingBox"] = {{r.bounding_box_min.x(), r.bounding_box_min.y(), r.bounding_box_min.z()},
                        {r.bounding_box_max.x(), r.bounding_box_max.y(), r.bounding_box_max.z()}};
    for (const CheckResult& c : r.checks)
        for (const Statistic& s : c.statistics)
            if (s.in_json)
                j[s.key] = statistic_json(s.value);
    j["minScaledJacobian"] = number(r.min_scaled_jacobian);
    j["failedChecks"] = r.failed_checks;
    j["failedCheckNames"] = r.failed_check_names;
    j["meshOK"] = r.mesh_ok();
    return j;
}

void print_quality_summary(std::ostream& out, const nlohmann::json& before,
                           const nlohmann::json& after, int precision)
{
    struct Row
    {
        const char* label;
        const char* key;
    };
    static const Row rows[] = {
        {"cells", "cells"},
        {"min volume", "minVolume"},
        {"total volume", "totalVolume"},
        {"negative volume cells", "negativeVolumeCells"},
        {"max aspect ratio", "maxAspectRatio"},
        {"max non-orthogonality [deg]", "maxNonOrthogonality"},
        {"avg non-orthogonality [deg]", "avgNonOrthogonality"},
        {"severely non-orth. faces", "severelyNonOrthogonalFaces"},
        {"max skewness", "maxSkewness"},
        {"highly skewed faces", "highlySkewedFaces"},
        {"wrongly oriented pyramids", "incorrectlyOrientedFacePyramids"},
        {"min determinant", "minDeterminant"},
        {"min face weight", "minFaceWeight"},
        {"min volume ratio", "minVolumeRatio"},
        {"concave cells", "concaveCells"},
        {"face tet errors", "faceTetErrors"},
        {"min scaled Jacobian", "minScaledJacobian"},
        {"failed checks", "failedChecks"},
    };
    const auto cell = [&](const nlohmann::json& j, const char* key) -> std::string
    {
        if (j.is_null() || !j.contains(key))
            return "";
        const nlohmann::json& v = j[key];
        if (v.is_null())
            return "-";
        if (v.is_number_integer())
            return std::to_string(v.get<long long>());
        if (v.is_number())
            return format_scalar(v.get<double>(), precision);
        return v.dump();
    };
    const bool has_before = !before.is_null(), has_after = !after.is_null();
    out << "    " << pad("metric", 31);
    if (has_before)
        out << pad("before", 16);
    if (has_after)
        out << "after";
    out << "\n";
    for (const Row& row : rows)
    {
        const std::string b = cell(before, row.key), a = cell(after, row.key);
        if (b.empty() && a.empty())
            continue;
        out << "    " << pad(row.label, 31);
        if (has_before)
            out << pad(b.empty() ? "-" : b, 16);
        if (has_after)
            out << (a.empty() ? "-" : a);
        out << "\n";
    }
    const auto ok = [](const nlohmann::json& j)
    { return j.value("meshOK", false) ? "Mesh OK" : "mesh checks failed"; };
    out << "    " << pad("verdict", 31);
    if (has_before)
        out << pad(ok(before), 16);
    if (has_after)
        out << ok(after);
    out << "\n";
}

} // namespace meshmorph
