// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The sections of benchPaper, one per benchmark of the paper's Sec. 3; each returns
//! the JSON the report generator (benchmarks/paper/paper_report.py) reads.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "paper_common.h"

namespace paper
{

//! The plane of Sec. 3.3, shared with Sec. 3.5: an n x n grid on [0,1]^2, `rings` border
//! rings fixed, the `disc` vertices nearest to the centre lifted by `lift` in z.
struct PlaneSetup
{
    Surface s;
    std::vector<int> role; //!< per vertex: 0 free, 1 handle, 2 fixed
    Points position, displacement;
};
PlaneSetup plane_setup(int n, int rings, Index disc, double lift);
//! "rbf", "dmffd" or "ffd" (qualitative) on a lattice x lattice x lattice over the plane's
//! box [0,1]^2 x [-0.5, 0.5] (1% margin in x and y), fitted to the plane's constraints.
std::unique_ptr<meshmorph::SpaceDeformation> plane_method(const std::string& method, int lattice,
                                                          const PlaneSetup& plane);

//! Sec. 3.1: handle basis for 427 constraints (Fig. 6) and the large-size study.
Json run_performance(const Options& options);
//! Sec. 3.2: DM-FFD clamping on a sphere (Fig. 8) and defective surface meshes.
Json run_robustness(const Options& options);
//! Sec. 3.3: mean curvature after the same handle deformation (Fig. 9).
Json run_quality(const Options& options);
//! Sec. 3.5: constraint residuals of FFD, DM-FFD and RBF against the lattice resolution.
Json run_precision(const Options& options);
//! Sec. 3.6.1: a pipe mesh's wall moved by an amplitude sweep (Fig. 14).
Json run_pipe(const Options& options);
//! Sec. 3.6.2 (Table 2): the motorBike, three rider handles lifted, outer boundary fixed.
Json run_motorbike(const Options& options);

} // namespace paper
