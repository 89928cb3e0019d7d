// SPDX-License-Identifier: GPL-3.0-or-later
// The reduction rule of each statistic follows from its key, as the check functions name
// them (minX, maxX, avgX, totalX, counts); the exceptions are listed in rule_of().
#include "meshmorph/quality/check_reduction.h"

#include <algorithm>
#include <string_view>

#include <nlohmann/json.hpp>

#include "meshmorph/quality/face_orthogonality.h"

namespace meshmorph
{

namespace
{

enum class Rule
{
    sum,
    min,
    max,
    average,
    master
};

Rule rule_of(const Statistic& s)
{
    const std::string_view key = s.key;
    // Computed over every rank before the checks, or not combinable (the wedge geometry).
    for (std::string_view k : {"regions", "regionDisconnected", "boundaryOpenness", "wedgeAngles",
                               "wedgeAxis", "offPlanePoint", "oppositeWedgeAxis"})
        if (key == k)
            return Rule::master;
    // checkMesh reduces the coupled mismatch with maxOp; flags are true only if true on all.
    if (key == "averageCoupledMismatch" || key == "offPlaneDistance" || key.starts_with("max"))
        return Rule::max;
    if (key == "boundaryDefinitionOK" || key == "emptyFacesDivisible" ||
        key == "nearPointDistance" || key.starts_with("min"))
        return Rule::min;
    if (key.starts_with("avg"))
        return Rule::average;
    return std::holds_alternative<Index>(s.value) || std::holds_alternative<double>(s.value) ||
                   std::holds_alternative<Statistic::Counts>(s.value)
               ? Rule::sum
               : Rule::master;
}

nlohmann::json to_json(const std::vector<CheckResult>& checks)
{
    nlohmann::json out = nlohmann::json::array();
    for (const CheckResult& c : checks)
    {
        nlohmann::json stats = nlohmann::json::array();
        for (const Statistic& s : c.statistics)
        {
            nlohmann::json v;
            if (const Index* i = std::get_if<Index>(&s.value))
                v = *i;
            else if (const double* d = std::get_if<double>(&s.value))
                v = *d;
            else if (const Statistic::Counts* counts = std::get_if<Statistic::Counts>(&s.value))
                v = *counts;
            stats.push_back({{"v", v}, {"s", s.parts_sum}, {"n", s.parts_count}});
        }
        nlohmann::json sets = nlohmann::json::array();
        for (const OffenderSet& o : c.sets)
            sets.push_back({{"name", o.set.name},
                            {"kind", static_cast<int>(o.set.kind)},
                            {"size", o.size()},
                            {"description", o.description}});
        out.push_back({{"failure", c.failure}, {"stats", stats}, {"sets", sets}});
    }
    return out;
}

//! Adds rank `other`'s value of `s` into s (the master's).
void combine(Statistic& s, const nlohmann::json& other)
{
    const nlohmann::json& v = other.at("v");
    switch (rule_of(s))
    {
    case Rule::master:
        return;
    case Rule::average:
        s.parts_sum += other.at("s").get<double>();
        s.parts_count += other.at("n").get<Index>();
        return;
    case Rule::min:
    case Rule::max:
        if (double* d = std::get_if<double>(&s.value))
            *d = rule_of(s) == Rule::min ? std::min(*d, v.get<double>())
                                         : std::max(*d, v.get<double>());
        else if (Index* i = std::get_if<Index>(&s.value))
            *i = rule_of(s) == Rule::min ? std::min(*i, v.get<Index>())
                                         : std::max(*i, v.get<Index>());
        return;
    case Rule::sum:
        if (double* d = std::get_if<double>(&s.value))
            *d += v.get<double>();
        else if (Index* i = std::get_if<Index>(&s.value))
            *i += v.get<Index>();
        else if (auto* counts = std::get_if<Statistic::Counts>(&s.value))
            for (const auto& [name, n] : v.get<Statistic::Counts>())
                for (auto& [own, total] : *counts)
                    if (own == name)
                        total += n;
        return;
    }
}

//! An average from its combined parts (the non-orthogonality's parts are cosines).
void finish_average(Statistic& s)
{
    if (rule_of(s) != Rule::average || s.parts_count == 0)
        return;
    const double mean = s.parts_sum / static_cast<double>(s.parts_count);
    s.value = s.key == "avgNonOrthogonality" ? non_orthogonality_degrees(mean) : mean;
}

//! Adds rank `other`'s sets into c's: sizes summed, sets only that rank has inserted after
//! the set before them there (so that the check's order of sets is kept).
void combine_sets(CheckResult& c, const nlohmann::json& other)
{
    for (OffenderSet& o : c.sets)
        o.total = o.size();
    std::size_t insert_at = 0;
    for (const nlohmann::json& s : other)
    {
        const std::string name = s.at("name").get<std::string>();
        auto it = std::find_if(c.sets.begin(), c.sets.end(),
                               [&](const OffenderSet& o) { return o.set.name == name; });
        if (it == c.sets.end())
        {
            OffenderSet added{{name, static_cast<MeshSet::Kind>(s.at("kind").get<int>()), {}},
                              s.at("description").get<std::string>(),
                              0};
            it = c.sets.insert(c.sets.begin() + static_cast<std::ptrdiff_t>(insert_at), added);
        }
        it->total += s.at("size").get<Index>();
        insert_at = static_cast<std::size_t>(it - c.sets.begin()) + 1;
    }
}

} // namespace

std::vector<CheckResult> reduce_check_results(const std::vector<CheckResult>& mine,
                                              const parallel::Communicator& comm)
{
    const std::vector<std::uint8_t> packed = nlohmann::json::to_msgpack(to_json(mine));
    const std::vector<std::string> all = comm.gather(std::string(packed.begin(), packed.end()));
    std::vector<CheckResult> out = mine;
    if (!comm.master())
        return out;
    for (CheckResult& c : out)
        for (OffenderSet& o : c.sets)
            o.total = o.size();
    for (std::size_t rank = 1; rank < all.size(); ++rank)
    {
        const nlohmann::json other = nlohmann::json::from_msgpack(all[rank]);
        for (std::size_t i = 0; i < out.size() && i < other.size(); ++i)
        {
            CheckResult& c = out[i];
            const nlohmann::json& o = other[i];
            if (c.failure.empty())
                c.failure = o.at("failure").get<std::string>();
            const nlohmann::json& stats = o.at("stats");
            for (std::size_t k = 0; k < c.statistics.size() && k < stats.size(); ++k)
                combine(c.statistics[k], stats[k]);
            combine_sets(c, o.at("sets"));
        }
    }
    for (CheckResult& c : out)
        for (Statistic& s : c.statistics)
            finish_average(s);
    return out;
}

} // namespace meshmorph
