// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: tree-accelerated inverse-distance weighted sums (the evaluation behind
//! IdwDeformation).
//!
//! For sources s_j with values v_j and the two-exponent weight
//!     w(r) = r^-a + beta r^-b,   r = |x - s_j| (normalised units),   a < b,
//! it computes N(x) = sum_j w (v_j - m) and D(x) = sum_j w and returns m + N / D, with m
//! the midrange of the values (a constant field comes out exact). Far source clusters
//! are replaced by a second-order Taylor expansion about their centroid (moments: count,
//! sum v, sum delta v^T, sum delta delta^T, sum delta delta^T v_k), the Barnes-Hut idea
//! that Luke, Collins & Blades (JCP 231, 2012) use for explicit mesh motion; near clusters
//! are summed directly. A cluster of radius rho is expanded for the points x with
//! rho < theta |x - centroid| (decided per point, so that a point's value does not depend
//! on the other points queried with it); theta = 0 sums every source directly (exact).
//!
//! The source tree cuts each node in the middle of its box's longest side (so that leaves do
//! not span the gaps between parts of a surface). Queries are sorted into compact blocks of
//! 32 (median cuts at multiples of 32, so that the blocks are full); each block builds one
//! interaction list
//! (each term with the block's points it applies to) from a compact copy of the nodes'
//! centroids and radii, and then runs SIMD loops over its points, so the cost per point is
//! a few hundred expansion and direct terms without per-point traversal. A query equal to a
//! source (a mesh morph evaluates its field at every constraint) takes that source's value
//! by a hash look-up, as the sum would give it.
//!
//! With the default weight (3, 5) and theta > 0 the terms are computed in single precision
//! (idw_kernels.h): 16 points per AVX-512 instruction instead of 8, for 0.7 of the time on
//! the motorBike. Offsets from a node's centroid are taken in double before they are
//! rounded, so a term's relative error is ~1e-7, far below the expansion's (~theta^3); the
//! motorBike's morphed points moved by 5e-8 of the largest displacement. A distance is
//! taken as at least 1e-8 of the sources' extent, which keeps r^-5 within float range; a
//! point nearer than that to a source (and not on it) still takes that source's value, to
//! single precision.
//! theta = 0 (the exact reference) and other weights sum in double.
//!
//! Quiet nodes. The error a far node's expansion adds to a point's mean is about the
//! expansion's relative error (which grows like theta^4 here) times
//! sum_j w_j |v_j - mean(x)| / D(x) over the node's sources. Where nearly every value is small
//! and a few are large (the residual of a global fit: within the fit's tolerance except on
//! the jumps it leaves out), a node of small values adds little error even expanded from
//! nearer. The caller says which sources are quiet (the correction: all but the global
//! fit's jumps, a choice made by the fit, not by comparing values here, so that it is the
//! same in every build); a node of quiet sources only is expanded when its radius is below
//! quiet_theta_factor x theta times the distance (1.75: 0.35 for the default 0.2), the
//! others keep theta. On the motorBike's IDW correction (5% lift: 497 of 56756 values on
//! jumps, up to 0.64 of the lift) the morph's evaluate stage went from 0.74 s to 0.46-0.50 s,
//! its error against the direct sum from 1.4e-4 to 2.5e-4 of the largest displacement; at a
//! 13.5% lift from 0.73 s to 0.40-0.41 s, error 3.3e-4 before and after. Factor 1.5: 1.5e-4 and
//! 3.1e-4; 2: 4.6e-4 and 7.1e-4, above the 6.6e-4 that theta 0.2 gives IDW of the
//! displacements. The same theta 0.3 for every node gave 6.2e-4 and 2.3e-3.
#pragma once

#include <cstdint>
#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/deform/exact_point_index.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/idw_node.h"

namespace meshmorph::detail
{

struct IdwWeight
{
    int far_exponent = 3;  //!< a
    int near_exponent = 5; //!< b > a
    double beta = 3.2e-4;  //!< alpha^b (alpha = 0.2)
};

//! theta's factor for quiet nodes (see above).
inline constexpr double quiet_theta_factor = 1.75;

class IdwTree
{
public:
    //! Sources in normalised coordinates (m x 3, m >= 1) and their values (m x 3); a node
    //! whose sources are all quiet (per source, 1: quiet) is a quiet node (see above); an
    //! empty `quiet`: none is.
    IdwTree(const Points& sources, const Points& values, const IdwWeight& weight, double theta,
            const std::vector<char>& quiet = {});

    //! \brief The locally essential tree for queries in the box lo..hi (normalised units),
    //! the parallel Barnes-Hut idea: a node far for every point of the box (radius < theta
    //! times its distance to the box) is written as its moments only; the others with their
    //! children, leaves with their sources. weighted_mean() of the tree read back equals this
    //! one's in the box, bit for bit.
    void write_essential(FieldWriter& out, const Vector3& lo, const Vector3& hi) const;
    //! \brief A tree written by write_essential(). \throw IoError on bad data.
    static IdwTree read_essential(FieldReader& in, const IdwWeight& weight, double theta);

    //! The weighted mean N(x) / D(x) at every normalised point (rows of x), or the value of
    //! a source that a point coincides with (the limit of the weighted mean there). OpenMP
    //! over query blocks; every point's sum runs in a fixed order (thread-count independent).
    void weighted_mean(const Points& x, Points& out) const;

    //! \brief The transpose of weighted_mean() as a map of the values: for weights g (a row
    //! per row of x) the m x 3 adjoint a of the values (rows in the order the sources were
    //! given), so that sum_i g_i . mean(x_i) = sum_j a_j . v_j for every v, with the tree's
    //! choices held (which nodes each point expands, which source it coincides with). The
    //! reverse pass of a sensitivity. Summed in double precision: against the forward sums'
    //! single precision the two sides agree to ~1e-6 relative. Deterministic: partial sums
    //! over a fixed partition of the query blocks, added in order (no thread-count effect).
    //! \throw std::logic_error for a tree read back for a region (read_essential: it has
    //! not every source).
    void weighted_mean_transpose(const Points& x, const Points& g, Points& out) const;

    //! Number of sources (after nothing is merged: coincident sources all count).
    Index size() const { return static_cast<Index>(sx_.size()); }

    //! The source a point equals exactly (tree order), or -1 when there is none or when
    //! another source of its leaf lies within the coincidence distance (then the sum
    //! decides which of their values the point takes).
    Index lone_source_at(double x, double y, double z) const;

    //! The records the evaluation kernels (idw_kernels.h) read: idw_node.h.
    using Node = IdwNode;
    using Probe = IdwProbe;
    using FarMoments = IdwFarMoments;

private:
    IdwTree(const IdwWeight& weight, double theta) : weight_(weight), theta_(theta) {}
    //! ux_, uy_, uz_ from the values and mid_.
    void shift_values();
    //! Opening radii of the quiet nodes (see the file's comment).
    void mark_quiet_nodes(const std::vector<char>& quiet, const std::vector<Index>& order);
    //! The traversal's probes and the nodes' moments in single precision.
    void index_probes();
    //! The sources relative to their leaf's centroid and their values, in single precision.
    void index_single_sources();
    void build(Index node, std::vector<Index>& order, const Points& s, const Points& v);
    void compute_moments(Node& node) const;
    void index_lone_sources();
    //! The weighted mean by the sum over the tree at the rows `rows` of x, into the same
    //! rows of out.
    void sum_over_tree(const Points& x, std::vector<Index> rows, Points& out) const;
    //! weighted_mean_transpose's sums over the tree for the rows `rows` of x, added to
    //! `adjoint` (m x 3 values, tree order, row-major).
    void transpose_over_tree(const Points& x, const Points& g, std::vector<Index> rows,
                             std::vector<double>& adjoint) const;
    //! Adds each node's adjoint moments (idw_tree_transpose.cpp) to its sources' adjoints.
    void push_to_sources(const std::vector<double>& node_adjoint,
                         std::vector<double>& adjoint) const;

    IdwWeight weight_;
    double theta_;
    std::vector<Node> nodes_;
    std::vector<Probe> probes_;         //!< per node, as nodes_
    std::vector<FarMoments> moments_f_; //!< per node, as nodes_
    //! The midrange of the values: the sums weight v - mid_, and the mean is mid_ + N / D,
    //! so that a constant field comes out exact and the sums hold smaller numbers.
    double mid_[3] = {0, 0, 0};
    //! The values minus mid_ (tree order), what the double-precision sums weight.
    std::vector<double> ux_, uy_, uz_;
    //! Sources relative to their leaf's centroid and the values minus mid_, in single
    //! precision (tree order), for the near-field kernel of the default weight.
    std::vector<float> ox_, oy_, oz_, fvx_, fvy_, fvz_;
    //! Tree order -> the sources' order as given (empty for a tree read_essential()).
    std::vector<Index> source_order_;
    // Sources and values in tree order, structure of arrays.
    std::vector<double> sx_, sy_, sz_, vx_, vy_, vz_;
    //! Exact coordinates (bit patterns, -0 as +0) of the sources without a coincident
    //! neighbour -> their tree index. A mesh morph evaluates the field at every constraint,
    //! and these points take their source's value without a sum over the tree.
    ExactPointIndex lone_;
};

} // namespace meshmorph::detail
