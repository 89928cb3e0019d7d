// SPDX-License-Identifier: GPL-3.0-or-later
// JSON form of a QualityReport (the mesh statistics, then every check result's statistics).
#include "meshmorph/quality/quality_json.h"

#include <cmath>

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

nlohmann::json failed_checks_json(const std::vector<std::pair<std::string, Index>>& failures)
{
    nlohmann::json list = nlohmann::json::array();
    for (const auto& [name, count] : failures)
        list.push_back({{"check", name}, {"count", count}});
    return list;
}

} // namespace meshmorph
