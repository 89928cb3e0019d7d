// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The part of a mesh's edge graph the jump smoothing works on, and its Laplacian.
//!
//! The band around a jump (jump_smoothing.h) is found along the mesh's edges, but a path of
//! length at most the band's width from a seed never leaves the ball of that radius around
//! it: the points within the width (straight line) of a seed, their edges, and the points
//! those edges reach hold everything the band's system needs. A serial morph builds this
//! graph from its mesh, a -parallel one gathers each rank's part on the master
//! (jump_smoothing_parallel.h); both solve it here, with the points ordered by their label
//! in the undecomposed mesh, so the result does not depend on the decomposition.
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/point_faces.h"

namespace meshmorph::morph::detail
{

//! The constraints on a jump of a prescription (the greedy RBF's default slope and width).
struct JumpSeeds
{
    std::vector<Index> labels; //!< ascending
    Points positions;          //!< where they were fitted (one row each)
    std::vector<char> moving;  //!< |prescription| above 1e-6 of the largest: the walls
    double width = 0.0;        //!< the band's width (distance along the edges)
};

//! \brief The seeds of a prescription: `labels` (ascending) fitted at `positions` to
//! `values`. Empty where the prescription has no jump.
JumpSeeds jump_seeds(const std::vector<Index>& labels, const Points& positions,
                     const Points& values);

//! \brief Per row of x, whether it lies within `width` (straight line) of a seed position.
//! \param stop_above when >= 0, the search stops once more points than this are reached
//! (the mask then holds more than stop_above, not all of them: enough for a cap's verdict).
std::vector<char> within_reach(const Points& x, const Points& seeds, double width,
                               Index stop_above = -1);

//! \brief How many entries of a within_reach mask are set.
Index count_reached(const std::vector<char>& reached);

//! The graph: nodes sorted by label. Nodes within reach list their neighbours; the others
//! are the border their edges reach.
struct BandGraph
{
    std::vector<Index> labels;
    Points x;                  //!< the points' positions (edge lengths)
    Points d;                  //!< the fitted field there
    std::vector<char> reached; //!< within reach: neighbours listed
    std::vector<char> constrained;
    std::vector<std::vector<Index>> neighbours; //!< node indices, ascending
    std::vector<Index> points; //!< the node's point in the mesh it came from (this rank's)

    Index size() const { return Index(labels.size()); }
    //! The node of a label (-1: none).
    Index node(Index label) const;
};

//! \brief The graph of `mesh` around the points `reached` (flags per point), with the field
//! `d` and the constrained flags per point; `label_of` maps a mesh point to its label (null:
//! a serial mesh, whose points are their own labels).
BandGraph local_band_graph(const PolyMesh& mesh, const std::vector<char>& reached,
                           const std::vector<char>& constrained, const Points& d,
                           const std::vector<Index>* label_of = nullptr);

//! The band's system on a graph: A u = sum over `border` of weight * d(node).
struct BandSystem
{
    std::vector<Index> band; //!< node indices of the unknowns, ascending
    double depth = 0.0;      //!< the largest distance of a band node from the jump
    struct Coupling
    {
        Eigen::Index row;
        Index node;
        double weight;
    };
    std::vector<Coupling> border;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor;
};

//! \brief The band of `seeds` in `g` and its factored system (an empty band: nothing).
//! \throw SolverError if it cannot be factored.
void band_system(const BandGraph& g, const JumpSeeds& seeds, BandSystem& s);

//! \brief The harmonic values of the band's nodes (one row each, as s.band).
Eigen::MatrixXd solve_band(const BandGraph& g, const BandSystem& s);

//! \brief The transpose: `weights` per node after the smoothing to before it (the band's
//! rows carried to the nodes its Laplacian reads, then zeroed).
void transpose_band(const BandSystem& s, Eigen::MatrixXd& weights);

} // namespace meshmorph::morph::detail
