// SPDX-License-Identifier: GPL-3.0-or-later
// Per point: gather the claims, judge their agreement, apply the conflict rule.
#include "meshmorph/morph/conflict_resolution.h"

#include <algorithm>
#include <cmath>

namespace meshmorph::morph
{

namespace
{

//! The claims of one point, by kind.
struct PointClaims
{
    Index point = 0;
    std::vector<const Claim*> values;
    std::vector<const Claim*> slips;
};

//! How the claims of a point relate.
struct Agreement
{
    bool conflict = false;
    bool values_agree = true;
    double spread = 0.0; //!< how far apart the prescriptions are
};

//! A motion leaves a slip (or wedge) plane when its normal component exceeds the tolerance
//! to which the patch was found planar, relative to the motion: a translation along a
//! wedge's axis, written to 6 digits, stays in both wedge planes.
Agreement assess(const PointClaims& pc, const ResolveSettings& s)
{
    Agreement a;
    if (pc.values.empty())
        return a;
    const Vector3& first = pc.values.front()->value;
    for (const Claim* c : pc.values)
    {
        a.spread = std::max(a.spread, (c->value - first).norm());
        if ((c->value - first).norm() > s.agree_tolerance)
            a.values_agree = false;
    }
    a.conflict = !a.values_agree;
    for (const Claim* slip : pc.slips)
    {
        const double off_plane = std::abs(first.dot(slip->value));
        a.spread = std::max(a.spread, off_plane);
        if (off_plane > s.in_plane_tolerance * first.norm() + s.agree_tolerance)
            a.conflict = true;
    }
    return a;
}

//! Projector removing the components along the given unit normals (an orthonormal basis of
//! their span is built first, so two nearly equal normals count once).
Eigen::Matrix3d slip_projector(const std::vector<const Claim*>& slips, int& rank)
{
    std::vector<Vector3> basis;
    for (const Claim* s : slips)
    {
        Vector3 v = s->value;
        for (const Vector3& b : basis)
            v -= v.dot(b) * b;
        // Planes within ~0.06 degrees of each other are the same plane here.
        if (v.norm() > 1e-3)
            basis.push_back(v.normalized());
    }
    rank = static_cast<int>(basis.size());
    Eigen::Matrix3d P = Eigen::Matrix3d::Identity();
    for (const Vector3& b : basis)
        P -= b * b.transpose();
    return P;
}

Resolved held(Index point)
{
    return {point, false, Vector3::Zero(), Eigen::Matrix3d::Identity(), -1};
}

//! Sliding within every plane of the point; three independent planes hold it.
Resolved sliding(Index point, const std::vector<const Claim*>& slips)
{
    int rank = 0;
    const Eigen::Matrix3d P = slip_projector(slips, rank);
    if (rank >= 3)
        return held(point);
    return {point, true, Vector3::Zero(), P, -1};
}

Resolved from_value(Index point, const Claim& c)
{
    return {point, false, c.value, Eigen::Matrix3d::Identity(), c.rotation};
}

//! Claims that agree: the common value (exactly in the slip planes, if any), or sliding.
Resolved agreed(const PointClaims& pc)
{
    if (pc.values.empty())
        return sliding(pc.point, pc.slips);
    Resolved r = from_value(pc.point, *pc.values.front());
    if (!pc.slips.empty()) // in the planes to round-off: exactly in them
        r.value = sliding(pc.point, pc.slips).projector * r.value;
    return r;
}

//! The claim whose entry is written first (last) among the values and slips.
const Claim* winner(const PointClaims& pc, bool first)
{
    const Claim* w = nullptr;
    for (const std::vector<const Claim*>* group : {&pc.values, &pc.slips})
        for (const Claim* c : *group)
            if (w == nullptr || (first ? c->order < w->order : c->order > w->order))
                w = c;
    return w;
}

Resolved by_rule(const PointClaims& pc, ConflictRule rule)
{
    switch (rule)
    {
    case ConflictRule::error:
    case ConflictRule::fixed:
        return held(pc.point);
    case ConflictRule::average:
    {
        Vector3 mean = Vector3::Zero();
        for (const Claim* c : pc.values)
            mean += c->value;
        mean /= static_cast<double>(pc.values.size());
        return {pc.point, false, mean, Eigen::Matrix3d::Identity(), -1};
    }
    case ConflictRule::first:
    case ConflictRule::last:
    {
        const Claim* w = winner(pc, rule == ConflictRule::first);
        return w->kind == Claim::Kind::slip ? sliding(pc.point, pc.slips)
                                            : from_value(pc.point, *w);
    }
    }
    return held(pc.point);
}

//! Near agreement (see the file comment): counted, and no longer a conflict unless the
//! values themselves differ.
bool near_agreement(const PointClaims& pc, const ResolveSettings& s, Agreement& a, Resolution& out)
{
    if (!a.conflict || s.shortest_edges == nullptr)
        return false;
    const double edge = (*s.shortest_edges)[static_cast<std::size_t>(pc.point)];
    if (a.spread > s.near_agreement * edge)
        return false;
    ++out.n_near_agreements;
    out.max_near_agreement = std::max(out.max_near_agreement, a.spread / edge);
    a.conflict = !a.values_agree;
    return true;
}

void resolve_point(const PointClaims& pc, const ResolveSettings& s, Resolution& out)
{
    if (pc.values.empty() && pc.slips.empty())
    {
        ++out.n_free;
        return;
    }
    Agreement a = assess(pc, s);
    const bool near = near_agreement(pc, s, a, out);
    if (!a.conflict)
    {
        out.points.push_back(agreed(pc));
        return;
    }
    if (!near)
    {
        ++out.n_conflicts;
        std::vector<const Claim*> all = pc.values;
        all.insert(all.end(), pc.slips.begin(), pc.slips.end());
        ++out.conflicts[s.conflict_name(all)];
    }
    out.points.push_back(by_rule(pc, s.rule));
}

} // namespace

std::vector<std::string> Resolution::conflict_summary() const
{
    std::vector<std::string> lines;
    for (const auto& [name, count] : conflicts)
        lines.push_back(name + ": " + std::to_string(count) + " points");
    return lines;
}

Resolution resolve(const std::vector<Claim>& claims, const ResolveSettings& settings)
{
    Resolution out;
    out.points.reserve(claims.size());
    for (std::size_t begin = 0; begin < claims.size();)
    {
        PointClaims pc;
        pc.point = claims[begin].point;
        std::size_t end = begin;
        for (; end < claims.size() && claims[end].point == pc.point; ++end)
        {
            if (claims[end].kind == Claim::Kind::value)
                pc.values.push_back(&claims[end]);
            else if (claims[end].kind == Claim::Kind::slip)
                pc.slips.push_back(&claims[end]);
        }
        resolve_point(pc, settings, out);
        begin = end;
    }
    return out;
}

} // namespace meshmorph::morph
