// SPDX-License-Identifier: GPL-3.0-or-later
// The greedy RBF fit's centres: farthest-point sampling, the jump constraints left out, and
// each round's batch (the largest residuals, or spread by octave and distance to the
// centres).
#include "meshmorph/deform/greedy_centres.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>

#include "meshmorph/core/log.h"
#include "meshmorph/core/tie_break.h"

namespace meshmorph::detail
{

namespace
{

//! Keeps the b candidates with the largest residuals, largest first (residuals equal but
//! for round-off tie, lowest index first).
void keep_largest_residuals(std::vector<Eigen::Index>& cand, const Eigen::VectorXd& err,
                            Eigen::Index b)
{
    const Eigen::VectorXd key = err.unaryExpr([](double e) { return coarsened(e); });
    std::partial_sort(cand.begin(), cand.begin() + b, cand.end(),
                      [&](Eigen::Index a, Eigen::Index c)
                      { return key[a] > key[c] || (key[a] == key[c] && a < c); });
    cand.resize(std::size_t(b));
}

//! A candidate of a spread round and its squared distance to the nearest centre, computed
//! once for the ordering and the batch's spacing test.
struct RankedCandidate
{
    Eigen::Index index;
    double to_centre2;
    double to_centre2_key; //!< coarsened(to_centre2), the sort key
};

//! The candidates grouped by their residual's octave (the binary exponent of residual /
//! unit), largest octave first, each group in index order. The residuals of a fit with
//! condition ~1e10 carry round-off of ~1e-6 relative, which differs between processors and
//! builds: ordered by the residuals themselves, two builds chose different centres on the
//! motorBike. The octave changes only where a residual lies within that round-off of a
//! power of two, so the groups are the same on every processor (the field still differs by
//! round-off times the condition number: docs/same-result.md).
std::vector<std::vector<Eigen::Index>> octaves(const std::vector<Eigen::Index>& cand,
                                               const Eigen::VectorXd& err, double unit)
{
    // Bucketed by octave (a handful per round) instead of sorting every candidate: the
    // same groups, each in index order.
    std::map<int, std::vector<Eigen::Index>> by_octave; // largest octave first: key -ilogb
    for (Eigen::Index j : cand)
        by_octave[-std::ilogb(err[j] / unit)].push_back(j);
    std::vector<std::vector<Eigen::Index>> groups;
    groups.reserve(by_octave.size());
    for (auto& [key, group] : by_octave)
    {
        if (!std::is_sorted(group.begin(), group.end()))
            std::sort(group.begin(), group.end());
        groups.push_back(std::move(group));
    }
    return groups;
}

//! Points as structure of arrays, so that the distance to the nearest one vectorises.
struct PointSet
{
    std::vector<double> x, y, z;
    void add(const Points& X, Eigen::Index k)
    {
        x.push_back(X(k, 0));
        y.push_back(X(k, 1));
        z.push_back(X(k, 2));
    }
    //! Squared distance from X's point k to the nearest point of the set (infinity if none).
    double nearest2(const Points& X, Eigen::Index k) const
    {
        const double px = X(k, 0), py = X(k, 1), pz = X(k, 2);
        double d2 = std::numeric_limits<double>::infinity();
        const std::size_t n = x.size();
#pragma omp simd reduction(min : d2)
        for (std::size_t j = 0; j < n; ++j)
        {
            const double dx = px - x[j], dy = py - y[j], dz = pz - z[j];
            d2 = std::min(d2, dx * dx + dy * dy + dz * dz);
        }
        return d2;
    }
};

//! Squared distance from each of X's points `queries` to the nearest point of `set`
//! (infinity if it is empty). Blocks of queries against one point of the set at a time, so
//! that the loop over a block vectorises without a reduction; each query's minimum is taken
//! over the set in order, so the values do not depend on the threads.
std::vector<double> nearest_distances2(const std::vector<Eigen::Index>& queries, const Points& X,
                                       const PointSet& set)
{
    constexpr std::size_t block = 64;
    const std::size_t n = queries.size(), m = set.x.size();
    std::vector<double> d2(n, std::numeric_limits<double>::infinity());
    const std::int64_t blocks = std::int64_t((n + block - 1) / block);
    // Blocks taken as threads come free (the check before the morph shares the cores).
#pragma omp parallel for schedule(dynamic, 4) if (n * m > 100000)
    for (std::int64_t b = 0; b < blocks; ++b)
    {
        const std::size_t i0 = std::size_t(b) * block, count = std::min(block, n - i0);
        alignas(64) double px[block], py[block], pz[block], best[block];
        for (std::size_t i = 0; i < block; ++i)
        {
            const Eigen::Index q = queries[i0 + std::min(i, count - 1)];
            px[i] = X(q, 0);
            py[i] = X(q, 1);
            pz[i] = X(q, 2);
            best[i] = std::numeric_limits<double>::infinity();
        }
        for (std::size_t j = 0; j < m; ++j)
        {
            const double xj = set.x[j], yj = set.y[j], zj = set.z[j];
#pragma omp simd
            for (std::size_t i = 0; i < block; ++i)
            {
                const double dx = px[i] - xj, dy = py[i] - yj, dz = pz[i] - zj;
                best[i] = std::min(best[i], dx * dx + dy * dy + dz * dz);
            }
        }
        std::copy(best, best + count, d2.begin() + std::ptrdiff_t(i0));
    }
    return d2;
}

//! One octave's candidates by decreasing distance to the nearest centre (coarsened: the
//! distances come from the coordinates alone, so every processor orders them alike), then
//! by index.
std::vector<RankedCandidate> farthest_first(const std::vector<Eigen::Index>& group, const Points& X,
                                            const PointSet& centres)
{
    const std::vector<double> d2 = nearest_distances2(group, X, centres);
    std::vector<RankedCandidate> ranked(group.size());
    for (std::size_t k = 0; k < group.size(); ++k)
        ranked[k] = {group[k], d2[k], coarsened(d2[k])};
    std::sort(ranked.begin(), ranked.end(),
              [](const RankedCandidate& a, const RankedCandidate& b)
              {
                  return a.to_centre2_key > b.to_centre2_key ||
                         (a.to_centre2_key == b.to_centre2_key && a.index < b.index);
              });
    return ranked;
}

//! Adds to the batch `kept`, up to b, candidates in priority order: each unless it lies
//! closer to a point already kept than spread x its distance to the nearest centre (compared
//! coarsened: tie_break.h). A new centre corrects the field within about that distance, so
//! the batch spreads over every region with a large residual instead of crowding the worst
//! one (the crowded batch makes the interpolant oscillate where the centres are sparse). The
//! first candidate of a round is always kept.
void spread_batch(const std::vector<RankedCandidate>& ranked, const Points& X, Eigen::Index b,
                  double spread, std::vector<Eigen::Index>& kept)
{
    // Some kept point is closer than the limit exactly when the nearest one is (coarsened()
    // is monotone).
    PointSet near;
    for (Eigen::Index k : kept)
        near.add(X, k);
    for (const RankedCandidate& c : ranked)
    {
        if (Eigen::Index(kept.size()) >= b)
            break;
        if (coarsened_less(near.nearest2(X, c.index), spread * spread * c.to_centre2))
            continue; // crowded
        kept.push_back(c.index);
        near.add(X, c.index);
    }
}

//! A spread round's batch (GreedySettings::spread): the candidates with a residual above
//! `floor` (the largest alone when none is, so that rounds progress), by octave, then
//! farthest first, spaced. An octave is ranked only if the batch is not full before it.
std::vector<Eigen::Index> spread_round(std::vector<Eigen::Index> cand, const Eigen::VectorXd& err,
                                       double floor, double unit, const Points& X,
                                       const std::vector<Eigen::Index>& centres, Eigen::Index b,
                                       double spread)
{
    std::vector<Eigen::Index> above; // only these are ranked
    for (Eigen::Index j : cand)
        if (coarsened_less(floor, err[j]))
            above.push_back(j);
    if (above.empty())
    {
        keep_largest_residuals(cand, err, 1);
        above = cand;
    }
    PointSet centre_set; // once for the round's octaves
    for (Eigen::Index j : centres)
        centre_set.add(X, j);
    std::vector<Eigen::Index> kept;
    for (const std::vector<Eigen::Index>& group : octaves(above, err, unit))
    {
        spread_batch(farthest_first(group, X, centre_set), X, b, spread, kept);
        if (Eigen::Index(kept.size()) >= b)
            break;
    }
    return kept;
}

} // namespace

JumpBand mark_jumps(const Points& X, const Eigen::MatrixXd& H, const GreedySettings& s,
                    CentreMarks& marks, Index& count)
{
    JumpBand band;
    std::vector<char> jump = jump_constraints(X, H, s.jump_slope, s.jump_width, band, count);
    if (!jump.empty())
        marks.jump = std::move(jump);
    return band;
}

void log_jumps(Index count, const JumpBand& band, const GreedySettings& s)
{
    auto line = log::info();
    line << "    greedy RBF: " << count
         << " constraints on jumps (displacement changing faster than " << band.slope
         << " times the distance, a band " << band.width << " wide: ";
    if (band.width > band.extent * s.jump_width)
        line << "jumpSlope " << s.jump_slope;
    else
        line << "jumpWidth " << s.jump_width << " of the moving constraints' extent "
             << band.extent;
    line << ") left to the local correction";
}

std::vector<Eigen::Index> farthest_point_centres(const Points& X, const Eigen::MatrixXd& H,
                                                 const std::vector<Eigen::Index>& U,
                                                 Eigen::Index n0, CentreMarks& marks)
{
    const Eigen::Index N = X.rows();
    std::vector<Eigen::Index> initial;
    Eigen::VectorXd mind = Eigen::VectorXd::Constant(N, std::numeric_limits<double>::infinity());
    const auto update = [&](Eigen::Index c)
    {
        for (Eigen::Index i = 0; i < N; ++i)
            mind[i] = std::min(mind[i], (X.row(i) - X.row(c)).squaredNorm());
    };
    for (Eigen::Index u : U)
        update(u);
    if (U.empty())
    {
        const Eigen::Index first = first_largest(H.rowwise().norm());
        initial.push_back(first);
        marks.is_centre[std::size_t(first)] = 1;
        update(first);
    }
    while (Eigen::Index(U.size() + initial.size()) < n0)
    {
        Eigen::Index best = -1;
        for (Eigen::Index i = 0; i < N; ++i)
            if (!marks.is_centre[std::size_t(i)] &&
                (best < 0 || coarsened_less(mind[best], mind[i])))
                best = i;
        if (best < 0)
            break;
        initial.push_back(best);
        marks.is_centre[std::size_t(best)] = 1;
        update(best);
    }
    return initial;
}

void add_centres(IncrementalSystem& system, const std::vector<Eigen::Index>& candidates,
                 CentreMarks& marks)
{
    std::vector<Eigen::Index> rest = candidates;
    while (!rest.empty())
    {
        Eigen::Index bad = -1;
        const Eigen::Index kept = system.add(rest, bad);
        for (Eigen::Index j = kept; j < Eigen::Index(rest.size()); ++j)
            marks.is_centre[std::size_t(rest[std::size_t(j)])] = 0;
        if (bad < 0)
            break;
        marks.rejected[std::size_t(bad)] = 1;
        rest.erase(rest.begin(), rest.begin() + kept + 1);
        for (Eigen::Index j : rest)
            marks.is_centre[std::size_t(j)] = 1;
    }
}

Eigen::VectorXd fitted_residuals(const Points& got, const Eigen::MatrixXd& H,
                                 const CentreMarks& marks, Eigen::Index& n_fitted)
{
    Eigen::VectorXd err = (Eigen::MatrixXd(got) - H).rowwise().norm();
    n_fitted = 0;
    for (Eigen::Index i = 0; i < err.size(); ++i)
        if (marks.jump[std::size_t(i)])
            err[i] = 0.0;
        else
            ++n_fitted;
    return err;
}

std::vector<Eigen::Index> candidates(const Eigen::VectorXd& err, const CentreMarks& marks)
{
    std::vector<Eigen::Index> cand;
    for (Eigen::Index i = 0; i < err.size(); ++i)
        if (!marks.is_centre[std::size_t(i)] && !marks.rejected[std::size_t(i)] &&
            !marks.jump[std::size_t(i)] && err[i] > 0.0)
            cand.push_back(i);
    return cand;
}

std::vector<Eigen::Index> next_batch(std::vector<Eigen::Index> cand, const Eigen::VectorXd& err,
                                     double max_err, double max_disp, const GreedySettings& s,
                                     const Points& X, const IncrementalSystem& system,
                                     Eigen::Index centres, Eigen::Index room)
{
    // Automatic: half the centres, at most 4096 a round (the new rows and columns of the
    // factor are r x b and b x b: 4096 keeps them below ~0.7 GB at r = 20000).
    const Eigen::Index b =
        s.batch_size > 0 ? s.batch_size : std::clamp<Eigen::Index>(centres / 2, 1, 4096);
    if (!(s.spread > 0.0))
    {
        keep_largest_residuals(cand, err, std::min({b, Eigen::Index(cand.size()), room}));
        return cand;
    }
    std::vector<Eigen::Index> taken(system.unisolvent());
    taken.insert(taken.end(), system.selected().begin(), system.selected().end());
    // Above the max tolerance while it is not met; then (the RMS one is not) any.
    const double floor = max_err > s.tolerance * max_disp ? s.tolerance * max_disp : 0.0;
    const double unit = s.tolerance > 0.0 ? s.tolerance * max_disp : max_disp;
    return spread_round(std::move(cand), err, floor, unit, X, taken, std::min(b, room), s.spread);
}

} // namespace meshmorph::detail
