// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/quality/quality_report.h"

#include <utility>

namespace meshmorph
{

QualityReport without_cell_fields(QualityReport r)
{
    for (Eigen::VectorXd* field :
         {&r.cell_non_orthogonality, &r.cell_skewness, &r.cell_aspect_ratio, &r.cell_determinant,
          &r.cell_scaled_jacobian})
        *field = Eigen::VectorXd();
    return r;
}

void summarise_checks(QualityReport& r)
{
    r.failed_checks = 0;
    r.failed_check_names.clear();
    r.sets.clear();
    if (!r.non_manifold_points.empty()) // written first, as checkMesh's topology does
        r.sets.push_back({"nonManifoldPoints", MeshSet::Kind::point, r.non_manifold_points});
    for (const CheckResult& c : r.checks)
    {
        if (c.failed())
        {
            ++r.failed_checks;
            r.failed_check_names.push_back(c.failure);
        }
        for (const OffenderSet& s : c.sets)
            r.sets.push_back(s.set);
    }
    const std::pair<Index QualityReport::*, const char*> counts[] = {
        {&QualityReport::negative_volume_cells, "negativeVolumeCells"},
        {&QualityReport::incorrectly_oriented_face_pyramids, "incorrectlyOrientedFacePyramids"},
        {&QualityReport::face_tet_errors, "faceTetErrors"}};
    for (const auto& [field, key] : counts)
        if (const Statistic* s = r.statistic(key))
            r.*field = std::get<Index>(s->value);
    const std::pair<double QualityReport::*, const char*> reals[] = {
        {&QualityReport::max_non_orthogonality, "maxNonOrthogonality"},
        {&QualityReport::max_skewness, "maxSkewness"},
        {&QualityReport::max_aspect_ratio, "maxAspectRatio"},
        {&QualityReport::total_volume, "totalVolume"},
        {&QualityReport::min_determinant, "minDeterminant"}};
    for (const auto& [field, key] : reals)
        if (const Statistic* s = r.statistic(key))
            r.*field = std::get<double>(s->value);
}

const Statistic* QualityReport::statistic(std::string_view key) const
{
    for (const CheckResult& c : checks)
        if (const Statistic* s = c.find(key))
            return s;
    return nullptr;
}

} // namespace meshmorph
