// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/quality/quality_summary.h"

#include <cmath>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <variant>

#include "meshmorph/core/number_format.h"

namespace meshmorph
{

namespace
{

//! One value of a table cell: a count or a real, or none (the report lacks it).
using Cell = std::optional<std::variant<Index, double>>;

struct Row
{
    const char* label;
    std::function<Cell(const QualityReport&)> value;
};

//! A statistic of any check, by the key the checks give it.
Cell statistic(const QualityReport& r, const char* key)
{
    const Statistic* s = r.statistic(key);
    if (s == nullptr)
        return std::nullopt;
    if (const Index* count = std::get_if<Index>(&s->value))
        return *count;
    if (const double* real = std::get_if<double>(&s->value))
        return *real;
    return std::nullopt;
}

Row stat_row(const char* label, const char* key)
{
    return {label, [key](const QualityReport& r) { return statistic(r, key); }};
}

const Row rows[] = {
    {"cells", [](const QualityReport& r) -> Cell { return r.n_cells; }},
    stat_row("min volume", "minVolume"),
    stat_row("total volume", "totalVolume"),
    stat_row("negative volume cells", "negativeVolumeCells"),
    stat_row("max aspect ratio", "maxAspectRatio"),
    stat_row("max non-orthogonality [deg]", "maxNonOrthogonality"),
    stat_row("avg non-orthogonality [deg]", "avgNonOrthogonality"),
    stat_row("severely non-orth. faces", "severelyNonOrthogonalFaces"),
    stat_row("max skewness", "maxSkewness"),
    stat_row("highly skewed faces", "highlySkewedFaces"),
    stat_row("wrongly oriented pyramids", "incorrectlyOrientedFacePyramids"),
    stat_row("min determinant", "minDeterminant"),
    stat_row("min face weight", "minFaceWeight"),
    stat_row("min volume ratio", "minVolumeRatio"),
    stat_row("concave cells", "concaveCells"),
    stat_row("face tet errors", "faceTetErrors"),
    {"min scaled Jacobian", [](const QualityReport& r) -> Cell { return r.min_scaled_jacobian; }},
    {"failed checks", [](const QualityReport& r) -> Cell { return r.failed_checks; }},
};

std::string text(const Cell& c, int precision)
{
    if (!c)
        return "";
    if (const Index* count = std::get_if<Index>(&*c))
        return std::to_string(*count);
    const double v = std::get<double>(*c);
    return std::isfinite(v) ? format_scalar(v, precision) : "-";
}

std::string pad(const std::string& s, std::size_t width)
{
    return s.size() >= width ? s + " " : s + std::string(width - s.size(), ' ');
}

const char* verdict(const QualityReport& r)
{
    return r.mesh_ok() ? "Mesh OK" : "mesh checks failed";
}

void print_row(std::ostream& out, const std::string& label, const std::string* before,
               const std::string* after)
{
    out << "    " << pad(label, 31);
    if (before)
        out << pad(before->empty() ? "-" : *before, 16);
    if (after)
        out << (after->empty() ? "-" : *after);
    out << "\n";
}

} // namespace

void print_quality_summary(std::ostream& out, const QualityReport* before,
                           const QualityReport* after, int precision)
{
    const std::string before_head = "before", after_head = "after";
    print_row(out, "metric", before ? &before_head : nullptr, after ? &after_head : nullptr);
    for (const Row& row : rows)
    {
        const std::string b = before ? text(row.value(*before), precision) : "";
        const std::string a = after ? text(row.value(*after), precision) : "";
        if (b.empty() && a.empty())
            continue;
        print_row(out, row.label, before ? &b : nullptr, after ? &a : nullptr);
    }
    const std::string b = before ? verdict(*before) : "", a = after ? verdict(*after) : "";
    print_row(out, "verdict", before ? &b : nullptr, after ? &a : nullptr);
}

} // namespace meshmorph
