// SPDX-License-Identifier: GPL-3.0-or-later
// Greedy RBF refinement with an incrementally extended Cholesky factor of the Lagrange
// null-space system (see the header for the formulation).
#include "meshmorph/deform/greedy_rbf_deformation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include <Eigen/LU>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/stopwatch.h"
#include "meshmorph/core/tie_break.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/jump_detection.h"
#include "meshmorph/deform/lapack.h"
#include "meshmorph/deform/rbf_evaluator.h"
#include "meshmorph/deform/rbf_setup.h"
#include "meshmorph/deform/row_panel_factor.h"

namespace meshmorph
{

namespace
{

//! The growing factorisation of the greedy fit (all in normalised coordinates).
class IncrementalSystem
{
public:
    IncrementalSystem(const detail::RbfModel& model, double sign, const Points& X,
                      const Eigen::MatrixXd& Pall, std::vector<Eigen::Index> unisolvent)
        : model_(model), sign_(sign), X_(X), P_(Pall), U_(std::move(unisolvent))
    {
        const Eigen::Index p = P_.cols();
        PU_.resize(p, p);
        AUU_.resize(p, p);
        for (Eigen::Index a = 0; a < p; ++a)
        {
            PU_.row(a) = P_.row(U_[std::size_t(a)]);
            for (Eigen::Index b = 0; b < p; ++b)
                AUU_(a, b) = phi(U_[std::size_t(a)], U_[std::size_t(b)]);
        }
        if (p > 0)
        {
            luT_.compute(PU_.transpose());
            lu_.compute(PU_);
        }
        Lam_.resize(p, 0);
        AU_.resize(p, 0);
    }

    Eigen::Index size() const { return r_; }
    const std::vector<Eigen::Index>& selected() const { return sel_; }
    const std::vector<Eigen::Index>& unisolvent() const { return U_; }

    //! Adds candidates in order; stops at the first one that would make the factor
    //! indefinite (returned in rejected, or -1). Returns the number added.
    Eigen::Index add(const std::vector<Eigen::Index>& cand, Eigen::Index& rejected)
    {
        rejected = -1;
        const Eigen::Index b = Eigen::Index(cand.size());
        const Eigen::Index p = P_.cols();
        const Eigen::Index r0 = r_;
        if (b == 0)
            return 0;
        Eigen::MatrixXd Lam_n(p, b), AU_n(p, b);
        for (Eigen::Index j = 0; j < b; ++j)
        {
            if (p > 0)
                Lam_n.col(j) = luT_.solve(P_.row(cand[std::size_t(j)]).transpose());
            for (Eigen::Index a = 0; a < p; ++a)
                AU_n(a, j) = phi(U_[std::size_t(a)], cand[std::size_t(j)]);
        }
        // The new columns projected on the null space of the polynomial block: entry (i, j)
        // loses A_i . Lam_j + L_i . G_j with G = AU_n - AUU Lam_n, where (A_i, L_i) are row
        // i's columns of AU_ and Lam_ (a centre) or of AU_n and Lam_n (a new one). Done
        // column by column beside the kernel values: as products of inner dimension p
        // (Eigen's GEMM, with r0 x b temporaries) it took longer than the kernel values.
        const Eigen::MatrixXd G =
            p > 0 ? Eigen::MatrixXd(AU_n - AUU_ * Lam_n) : Eigen::MatrixXd(0, b);
        Eigen::MatrixXd Kon(r0, b), Knn(b, b);
        // Columns taken as threads come free: the check before the morph shares the cores.
#pragma omp parallel for schedule(dynamic, 4) if ((r0 + b) * b > 20000)
        for (Eigen::Index j = 0; j < b; ++j)
        {
            // Squared distances first, then the kernel over the column in one vectorised
            // pass: the same values as phi() element by element.
            for (Eigen::Index i = 0; i < r0; ++i)
                Kon(i, j) = distance2(sel_[std::size_t(i)], cand[std::size_t(j)]);
            for (Eigen::Index i = 0; i < b; ++i)
                Knn(i, j) = distance2(cand[std::size_t(i)], cand[std::size_t(j)]);
            model_.kernel.values_in_place(Kon.col(j).data(), std::size_t(r0));
            model_.kernel.values_in_place(Knn.col(j).data(), std::size_t(b));
            if (p > 0)
            {
                subtract_projection(AU_, Lam_, Lam_n.col(j).data(), G.col(j).data(),
                                    Kon.col(j).data());
                subtract_projection(AU_n, Lam_n, Lam_n.col(j).data(), G.col(j).data(),
                                    Knn.col(j).data());
            }
            Kon.col(j) *= sign_;
            Knn.col(j) *= sign_;
        }
        factor_.forward(Kon);
        // The Schur complement S = Knn - Kon^T Kon (lower triangle, what dpotrf reads) by
        // BLAS, which runs on one thread here: Eigen's product splits its blocks by the
        // number of OpenMP threads, and the last bits of S, then the centres chosen from
        // residuals amplified by the condition number, would follow the thread count.
        Eigen::MatrixXd S = Knn;
        const int n = detail::lapack_int(b);
        if (r0 > 0)
        {
            const int k = detail::lapack_int(r0);
            const double minus_one = -1.0, one = 1.0;
            dsyrk_("L", "T", &n, &k, &minus_one, Kon.data(), &k, &one, S.data(), &n);
        }
        int info = 0;
        dpotrf_("L", &n, S.data(), &n, &info);
        Eigen::Index keep = b;
        if (info > 0)
        {
            keep = info - 1;
            rejected = cand[std::size_t(keep)];
        }
        factor_.append(Kon.leftCols(keep).transpose(), S.topLeftCorner(keep, keep));
        Lam_.conservativeResize(p, r0 + keep);
        AU_.conservativeResize(p, r0 + keep);
        Lam_.rightCols(keep) = Lam_n.leftCols(keep);
        AU_.rightCols(keep) = AU_n.leftCols(keep);
        for (Eigen::Index j = 0; j < keep; ++j)
            sel_.push_back(cand[std::size_t(j)]);
        r_ = r0 + keep;
        return keep;
    }

    //! Weights of [U; selected] (rows) and polynomial coefficients for displacements H.
    void solve(const Eigen::MatrixXd& H, Eigen::MatrixXd& W, Eigen::MatrixXd& Q) const
    {
        const Eigen::Index p = P_.cols();
        const Eigen::Index nc = H.cols();
        Eigen::MatrixXd HU(p, nc);
        for (Eigen::Index a = 0; a < p; ++a)
            HU.row(a) = H.row(U_[std::size_t(a)]);
        Eigen::MatrixXd Y(r_, nc);
        for (Eigen::Index i = 0; i < r_; ++i)
            Y.row(i) = H.row(sel_[std::size_t(i)]);
        if (p > 0)
            Y -= Lam_.transpose() * HU;
        Y *= sign_;
        factor_.forward(Y);
        factor_.backward(Y);
        W.resize(p + r_, nc);
        W.bottomRows(r_) = Y;
        if (p > 0)
        {
            W.topRows(p) = -Lam_ * Y;
            Q = lu_.solve(HU - AUU_ * W.topRows(p) - AU_ * Y);
        }
        else
        {
            Q.resize(0, nc);
        }
    }

    //! Keeps the first r selected centres. The leading r x r block of a Cholesky factor is
    //! the factor of the leading block, so nothing is recomputed.
    void truncate(Eigen::Index r)
    {
        if (r >= r_)
            return;
        sel_.resize(std::size_t(r));
        Lam_.conservativeResize(Lam_.rows(), r);
        AU_.conservativeResize(AU_.rows(), r);
        factor_.truncate(r);
        r_ = r;
    }

    double condition_lower_bound() const
    {
        if (r_ == 0)
            return 1.0;
        const Eigen::VectorXd d = factor_.diagonal().cwiseAbs();
        const double ratio = d.maxCoeff() / d.minCoeff();
        return ratio * ratio;
    }

private:
    //! x_i -= A(:, i) . lam + L(:, i) . g for the A.cols() rows of x (A and L: p x n).
    static void subtract_projection(const Eigen::MatrixXd& A, const Eigen::MatrixXd& L,
                                    const double* lam, const double* g, double* x)
    {
        const Eigen::Index p = A.rows();
        for (Eigen::Index i = 0; i < A.cols(); ++i)
        {
            const double* a = A.col(i).data();
            const double* l = L.col(i).data();
            double s = 0.0;
            for (Eigen::Index k = 0; k < p; ++k)
                s += a[k] * lam[k] + l[k] * g[k];
            x[i] -= s;
        }
    }
    double distance2(Eigen::Index i, Eigen::Index j) const
    {
        return (X_.row(i) - X_.row(j)).squaredNorm();
    }
    double phi(Eigen::Index i, Eigen::Index j) const
    {
        return model_.kernel.value(distance2(i, j));
    }
    const detail::RbfModel& model_;
    double sign_;
    const Points& X_;
    const Eigen::MatrixXd& P_;
    std::vector<Eigen::Index> U_;
    Eigen::MatrixXd PU_, AUU_, Lam_, AU_;
    detail::RowPanelFactor factor_; //!< of the selected centres' null-space system
    Eigen::FullPivLU<Eigen::MatrixXd> luT_, lu_;
    std::vector<Eigen::Index> sel_;
    Eigen::Index r_ = 0;
};

//! Rows of P (one per constraint, one column per polynomial term) forming a well-spread
//! unisolvent set: QR with column pivoting on P^T, pivoting on the largest remaining row
//! norm with round-off ties going to the lowest row (first_largest), so that a symmetric
//! mesh gets the same set on every processor.
std::vector<Eigen::Index> unisolvent_rows(const Eigen::MatrixXd& P)
{
    Eigen::MatrixXd R = P;
    std::vector<Eigen::Index> rows;
    for (Eigen::Index k = 0; k < P.cols(); ++k)
    {
        const Eigen::Index i = first_largest(R.rowwise().squaredNorm());
        const double norm = R.row(i).norm();
        if (!(norm > 0.0)) // choose_polynomial keeps only terms the constraints determine
            throw SolverError("greedy RBF: the constraints do not determine the polynomial "
                              "terms (too few or degenerate points): set rbf { polynomial none; }");
        const Eigen::VectorXd q = R.row(i).transpose() / norm;
        R -= (R * q) * q.transpose();
        R.row(i).setZero();
        rows.push_back(i);
    }
    return rows;
}

} // namespace

struct GreedyRbfDeformation::Impl
{
    GreedySettings settings;
    detail::RbfKernelSetup setup;
    detail::RbfModel model;
    FitReport report;
    bool fitted = false;
    bool converged = false;
    bool stopped_growing = false; //!< stopped because the residual grew (see fit())
    Index jump_constraints = 0;   //!< left out of the fit (GreedySettings::jump_slope, jump_width)
    std::vector<Index> centre_indices;
    std::vector<double> history;
    std::vector<double> rms_history;
    //! The model at every constraint of the last fit (values_at_handles()).
    Points values_at_handles;
    //! Per constraint of the last fit: on a jump (handles_left_out()).
    std::vector<char> left_out;
    // Kept after fit for handle_basis(); system refers to model, merged.centres and P.
    Index num_inputs = 0;
    detail::MergedHandles merged;
    Eigen::MatrixXd P;
    std::unique_ptr<IncrementalSystem> system;
};

GreedyRbfDeformation::GreedyRbfDeformation(const GreedySettings& settings)
    : impl_(std::make_unique<Impl>())
{
    impl_->settings = settings;
    impl_->setup = detail::rbf_kernel_setup(settings.rbf);
    if (!(settings.tolerance >= 0.0) || !(settings.rms_tolerance >= 0.0))
        throw InvalidInput("greedy RBF tolerances must be >= 0");
    if (!(settings.spread >= 0.0) || !(settings.jump_slope >= 0.0) || !(settings.jump_width >= 0.0))
        throw InvalidInput("greedy RBF: spread, jumpSlope and jumpWidth must be >= 0 (0: off)");
    if (settings.max_centres < 1 || settings.initial_centres < 0 || settings.batch_size < 0)
        throw InvalidInput("greedy RBF: max_centres must be >= 1, initial_centres and "
                           "batch_size >= 0");
}

GreedyRbfDeformation::~GreedyRbfDeformation() = default;
GreedyRbfDeformation::GreedyRbfDeformation(GreedyRbfDeformation&&) noexcept = default;
GreedyRbfDeformation& GreedyRbfDeformation::operator=(GreedyRbfDeformation&&) noexcept = default;

//! Which constraints are centres, and which the factor refused (linearly dependent).
struct detail::CentreMarks
{
    explicit CentreMarks(Eigen::Index n)
        : is_centre(std::size_t(n), 0), rejected(std::size_t(n), 0), jump(std::size_t(n), 0)
    {
    }
    std::vector<char> is_centre, rejected, jump;
};

namespace
{

using detail::CentreMarks;

//! Farthest-point sampling for the initial centres, seeded by the unisolvent set U (or the
//! largest displacement when there is no polynomial); n0 centres in all. Distances equal
//! but for round-off (symmetric meshes) tie, to the lowest index.
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

//! Adds the candidates in order; one the factor refuses is marked rejected and skipped.
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

//! The constraints that may become centres: not centres yet, not refused, with a residual.
std::vector<Eigen::Index> candidates(const Eigen::VectorXd& err, const CentreMarks& marks)
{
    std::vector<Eigen::Index> cand;
    for (Eigen::Index i = 0; i < err.size(); ++i)
        if (!marks.is_centre[std::size_t(i)] && !marks.rejected[std::size_t(i)] &&
            !marks.jump[std::size_t(i)] && err[i] > 0.0)
            cand.push_back(i);
    return cand;
}

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

//! Marks the constraints on a near-discontinuity of the data (detail::jump_constraints) and
//! returns the band.
detail::JumpBand mark_jumps(const Points& X, const Eigen::MatrixXd& H, const GreedySettings& s,
                            CentreMarks& marks, Index& count)
{
    detail::JumpBand band;
    std::vector<char> jump =
        detail::jump_constraints(X, H, s.jump_slope, s.jump_width, band, count);
    if (!jump.empty())
        marks.jump = std::move(jump);
    return band;
}

//! The log line of the jumps left out.
void log_jumps(Index count, const detail::JumpBand& band, const GreedySettings& s)
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

//! |model - data| at every constraint, 0 at the jump constraints (never fitted); their
//! number left out of `n_fitted`.
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

//! The next round's centres among the candidates: a spread batch (GreedySettings::spread)
//! or the largest residuals, at most `room` of them.
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

} // namespace

void GreedyRbfDeformation::prepare(const Eigen::Ref<const Points>& constraints,
                                   const Eigen::Ref<const Points>& displacements)
{
    Impl& d = *impl_;
    d.fitted = false;
    d.converged = false;
    d.stopped_growing = false;
    d.jump_constraints = 0;
    d.history.clear();
    d.rms_history.clear();
    d.report = FitReport{};
    d.report.method = "greedy-rbf";
    d.report.solver = "incremental Lagrange null-space Cholesky (dtrsm + dpotrf)";
    d.model = detail::normalised_model(d.setup, constraints);
    d.system.reset();
    d.merged = detail::merge_duplicates(constraints, d.model.normalise(constraints), displacements,
                                        d.settings.rbf.duplicate_tolerance);
    d.num_inputs = Index(constraints.rows());
    detail::choose_polynomial(d.model, d.setup.degree, d.merged.centres,
                              d.settings.rbf.polynomial_rank_tolerance);
    d.P = d.model.polynomial_matrix(d.merged.centres);
}

void GreedyRbfDeformation::set_model(const Eigen::MatrixXd& H)
{
    Impl& d = *impl_;
    const IncrementalSystem& system = *d.system;
    const Points& X = d.merged.centres;
    const Eigen::Index p = d.P.cols();
    Eigen::MatrixXd W, Q;
    system.solve(H, W, Q);
    Points C(p + system.size(), 3);
    for (Eigen::Index a = 0; a < p; ++a)
        C.row(a) = X.row(system.unisolvent()[std::size_t(a)]);
    for (Eigen::Index i = 0; i < system.size(); ++i)
        C.row(p + i) = X.row(system.selected()[std::size_t(i)]);
    d.model.set_centres(C);
    d.model.set_coefficients(W, Q);
}

void GreedyRbfDeformation::fit(const Eigen::Ref<const Points>& constraints,
                               const Eigen::Ref<const Points>& displacements)
{
    detail::check_fit_arguments(constraints, displacements);
    const Stopwatch clock;
    prepare(constraints, displacements);
    Impl& d = *impl_;
    const GreedySettings& s = d.settings;
    const Points& X = d.merged.centres;
    const Eigen::MatrixXd H = d.merged.displacements;
    const Eigen::Index N = X.rows(), p = d.P.cols();
    Points Xphys(N, 3);
    for (Eigen::Index i = 0; i < N; ++i)
        Xphys.row(i) = constraints.row(d.merged.first[std::size_t(i)]);

    const std::vector<Eigen::Index> U = unisolvent_rows(d.P);
    CentreMarks marks(N);
    const detail::JumpBand band = mark_jumps(Xphys, H, s, marks, d.jump_constraints);
    if (d.jump_constraints > 0)
        log_jumps(d.jump_constraints, band, s);
    for (Eigen::Index u : U)
        marks.is_centre[std::size_t(u)] = 1;
    const Eigen::Index budget = std::max<Eigen::Index>(s.max_centres, p);
    const Eigen::Index n0 =
        std::min({s.initial_centres > 0 ? s.initial_centres
                                        : std::max<Eigen::Index>(p, std::min<Eigen::Index>(20, N)),
                  N, budget});
    const std::vector<Eigen::Index> initial = farthest_point_centres(X, H, U, n0, marks);
    d.system = std::make_unique<IncrementalSystem>(d.model, d.setup.sign, X, d.P, U);
    add_centres(*d.system, initial, marks);
    Points round_values; // the model at the kept handles after the last round
    const Eigen::Index iterations = refine(Xphys, H, budget, marks, clock, round_values);
    d.left_out.resize(std::size_t(d.num_inputs));
    for (std::size_t i = 0; i < d.left_out.size(); ++i)
        d.left_out[i] = marks.jump[std::size_t(d.merged.representative[i])];
    finish_report(constraints, displacements, Index(iterations), budget, round_values);
}

Eigen::Index GreedyRbfDeformation::refine(const Points& Xphys, const Eigen::MatrixXd& H,
                                          Eigen::Index budget, CentreMarks& marks,
                                          const Stopwatch& clock, Points& got)
{
    Impl& d = *impl_;
    const GreedySettings& s = d.settings;
    IncrementalSystem& system = *d.system;
    const Eigen::Index N = Xphys.rows(), p = d.P.cols();
    const double max_disp = H.rows() > 0 ? H.rowwise().norm().maxCoeff() : 0.0;
    const double rel = 1.0 / std::max(max_disp, 1e-300);
    got.resize(N, 3);
    Eigen::Index iterations = 0;
    double best_rms = std::numeric_limits<double>::infinity();
    Eigen::Index best_size = 0;
    while (true)
    {
        set_model(H);
        d.model.evaluate(Xphys, got);
        Eigen::Index n_fitted = 0;
        const Eigen::VectorXd err = fitted_residuals(got, H, marks, n_fitted);
        const double max_err = err.maxCoeff();
        const double rms =
            std::sqrt(err.squaredNorm() / double(std::max<Eigen::Index>(n_fitted, 1)));
        d.history.push_back(max_err);
        d.rms_history.push_back(rms);
        log::info() << "    greedy RBF round " << iterations << ": " << p + system.size()
                    << " centres, max residual " << max_err * rel << ", rms " << rms * rel
                    << " (relative), " << clock.seconds() << " s";
        if (max_err <= s.tolerance * max_disp && rms <= s.rms_tolerance * max_disp)
        {
            d.converged = true;
            return iterations;
        }
        if (rms > best_rms && !(s.spread > 0.0))
        {
            // More centres made the fit worse: the data vary too sharply for a global
            // interpolant at this resolution (a moving wall touching a fixed one), and the
            // interpolant oscillates. Keep the best round; the caller's local correction
            // (CorrectedDeformation) takes up the rest.
            system.truncate(best_size);
            set_model(H);
            got.resize(0, 3); // the values of a model no longer kept
            d.stopped_growing = true;
            d.history.pop_back(); // the histories end with the model kept
            d.rms_history.pop_back();
            log::info() << "    greedy RBF: the rms residual grew (" << rms * rel << " > "
                        << best_rms * rel << "): keeping the " << p + best_size
                        << " centres of the best round";
            return iterations - 1;
        }
        if (rms <= best_rms)
        {
            best_rms = rms;
            best_size = system.size();
        }
        std::vector<Eigen::Index> cand = candidates(err, marks);
        if (cand.empty())
        {
            d.converged = true; // every constraint is a centre: interpolated exactly
            return iterations;
        }
        const Eigen::Index centres = p + system.size();
        if (centres >= budget)
            return iterations;
        cand = next_batch(std::move(cand), err, max_err, max_disp, s, d.merged.centres, system,
                          centres, budget - centres);
        for (Eigen::Index j : cand)
            marks.is_centre[std::size_t(j)] = 1;
        add_centres(system, cand, marks);
        ++iterations;
    }
}

//! The model at every constraint. A constraint that is the point of its kept handle takes
//! the last round's value there (the evaluation of the same point by the same model, bit
//! for bit); the others (merged duplicates, or all after a truncated refinement) are
//! evaluated. This spares the morph an evaluation at every constraint (1e8 kernel values
//! on the motorBike).
Points GreedyRbfDeformation::values_at_constraints(const Impl& d,
                                                   const Eigen::Ref<const Points>& constraints,
                                                   const Points& round_values)
{
    const Eigen::Index m = constraints.rows();
    Points values(m, 3);
    std::vector<Eigen::Index> rest;
    const bool have_round = round_values.rows() == Eigen::Index(d.merged.first.size());
    for (Eigen::Index c = 0; c < m; ++c)
    {
        const Index kept = d.merged.representative[std::size_t(c)];
        if (have_round && d.merged.first[std::size_t(kept)] == c)
            values.row(c) = round_values.row(kept);
        else
            rest.push_back(c);
    }
    if (rest.empty())
        return values;
    Points at(Eigen::Index(rest.size()), 3), got(Eigen::Index(rest.size()), 3);
    for (std::size_t k = 0; k < rest.size(); ++k)
        at.row(Eigen::Index(k)) = constraints.row(rest[k]);
    d.model.evaluate(at, got);
    for (std::size_t k = 0; k < rest.size(); ++k)
        values.row(rest[k]) = got.row(Eigen::Index(k));
    return values;
}

const std::vector<char>* GreedyRbfDeformation::handles_left_out() const
{
    return impl_->fitted && impl_->jump_constraints > 0 ? &impl_->left_out : nullptr;
}

const Points* GreedyRbfDeformation::values_at_handles() const
{
    return impl_->fitted ? &impl_->values_at_handles : nullptr;
}

void GreedyRbfDeformation::finish_report(const Eigen::Ref<const Points>& constraints,
                                         const Eigen::Ref<const Points>& displacements,
                                         Index iterations, Eigen::Index budget,
                                         const Points& round_values)
{
    Impl& d = *impl_;
    const IncrementalSystem& system = *d.system;
    const Eigen::Index p = d.P.cols();
    d.centre_indices.clear();
    for (Eigen::Index a = 0; a < p; ++a)
        d.centre_indices.push_back(
            d.merged.first[std::size_t(system.unisolvent()[std::size_t(a)])]);
    for (Eigen::Index j : system.selected())
        d.centre_indices.push_back(d.merged.first[std::size_t(j)]);
    d.fitted = true;
    d.report.num_handles = Index(d.merged.centres.rows());
    d.report.num_merged_duplicates = Index(constraints.rows() - d.merged.centres.rows());
    d.report.num_centres = Index(d.centre_indices.size());
    d.report.polynomial_terms = Index(p);
    d.report.iterations = iterations;
    d.report.condition_estimate = system.condition_lower_bound();
    d.values_at_handles = values_at_constraints(d, constraints, round_values);
    detail::residual_report(d.values_at_handles, displacements, d.report);
    d.report.jump_constraints = d.jump_constraints;
    if (d.jump_constraints > 0 && !d.history.empty())
        d.report.max_fitted_residual = d.history.back(); // the kept round's, over the others
    if (!d.converged && !d.stopped_growing)
    {
        const double max_disp = d.merged.displacements.rows() > 0
                                    ? d.merged.displacements.rowwise().norm().maxCoeff()
                                    : 0.0;
        const double rel = 1.0 / std::max(max_disp, 1e-300);
        // The tolerance applies to the constraints the global part fits (not the jumps).
        const double fitted =
            d.jump_constraints > 0 ? d.report.max_fitted_residual : d.report.max_residual;
        log::info() << "    greedy RBF: the budget of " << budget << " centres (maxCentres) "
                    << "ends the refinement at max residual " << fitted * rel
                    << " (relative, on the constraints it fits; tolerance " << d.settings.tolerance
                    << "; a larger maxCentres refines further)";
    }
}

void GreedyRbfDeformation::write_field(FieldWriter& out) const
{
    if (!impl_->fitted)
        throw InvalidInput("greedy RBF: write_field before fit");
    out.put(FieldKind::rbf);
    impl_->model.write(out);
}

void GreedyRbfDeformation::evaluate(const Eigen::Ref<const Points>& points,
                                    Eigen::Ref<Points> out) const
{
    detail::check_evaluate_arguments(impl_->fitted, points, out, "greedy RBF");
    impl_->model.evaluate(points, out);
}

const FitReport& GreedyRbfDeformation::report() const
{
    return impl_->report;
}
bool GreedyRbfDeformation::is_fitted() const
{
    return impl_->fitted;
}
bool GreedyRbfDeformation::converged() const
{
    return impl_->converged;
}
const std::vector<Index>& GreedyRbfDeformation::centre_indices() const
{
    return impl_->centre_indices;
}
const std::vector<double>& GreedyRbfDeformation::history() const
{
    return impl_->history;
}
const std::vector<double>& GreedyRbfDeformation::rms_history() const
{
    return impl_->rms_history;
}
bool GreedyRbfDeformation::stopped_growing() const
{
    return impl_->stopped_growing;
}
Index GreedyRbfDeformation::jump_constraints() const
{
    return impl_->jump_constraints;
}

Eigen::MatrixXd GreedyRbfDeformation::handle_basis(const Eigen::Ref<const Points>& points) const
{
    const Impl& d = *impl_;
    if (!d.fitted)
        throw InvalidInput("greedy RBF: handle_basis() called before fit()");
    detail::require_finite(points, "greedy RBF handle basis: point");
    const IncrementalSystem& system = *d.system;
    const Eigen::Index p = d.P.cols();
    const Eigen::Index c = p + system.size();
    // Unit displacement of each centre in turn (rows of the merged constraints).
    std::vector<Eigen::Index> rows(system.unisolvent());
    rows.insert(rows.end(), system.selected().begin(), system.selected().end());
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(d.merged.centres.rows(), c);
    for (Eigen::Index i = 0; i < c; ++i)
        E(rows[std::size_t(i)], i) = 1.0;
    Eigen::MatrixXd W, Q;
    system.solve(E, W, Q);
    const Points xn = d.model.normalise(points);
    Eigen::MatrixXd Bc = d.model.kernel_matrix(xn) * W;
    if (p > 0)
        Bc.noalias() += d.model.polynomial_matrix(xn) * Q;
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(points.rows(), d.num_inputs);
    for (Eigen::Index i = 0; i < c; ++i)
        B.col(d.merged.first[std::size_t(rows[std::size_t(i)])]) = Bc.col(i);
    return B;
}

} // namespace meshmorph
