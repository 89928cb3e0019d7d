// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Shared pieces of benchPaper, the C++ half of the paper benchmarks
//! (benchmarks/paper/deformationBenchmarks drives it): options, clocks, JSON output, the
//! synthetic geometry of the paper's set-ups (plane grid, sphere), residuals, the
//! "qualitative" FFD set-up and surface curvature statistics.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshmorph/core/types.h"
#include "meshmorph/deform/ffd_deformation.h"
#include "meshmorph/deform/space_deformation.h"
#include "meshmorph/quality/mean_curvature.h"

namespace paper
{
using meshmorph::Index;
using meshmorph::Points;
using meshmorph::Triangles;
using meshmorph::Vector3;
using Json = nlohmann::ordered_json;

//! Command line of one section: `benchPaper <section> -out FILE [-quick] [-key value ...]`.
struct Options
{
    bool quick = false;
    std::filesystem::path out;                //!< JSON result file
    std::map<std::string, std::string> value; //!< every other `-key value`

    //! The value of -key, or fallback.
    std::string get(const std::string& key, const std::string& fallback) const;
    double number(const std::string& key, double fallback) const;
};

//! Wall-clock seconds since an arbitrary origin.
inline double now()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

//! Writes json to path (pretty, 1 space indent); \throw meshmorph::IoError.
void write_json(const std::filesystem::path& path, const Json& json);

//! Row-major matrix as a JSON array of rows, each value rounded to `digits` significant digits
//! (the report's plots need no more; keeps the files small).
Json rows_json(const Points& p, int digits = 7);
Json rows_json(const Triangles& t);
Json vector_json(const Eigen::VectorXd& v, int digits = 7);

//! A triangle surface.
struct Surface
{
    Points vertices;
    Triangles triangles;
};

//! Regular n x n grid on [0,1]^2 in the plane z = 0, two triangles per cell, diagonals
//! alternating (a "criss-cross-free" union-jack pattern, no preferred direction).
//! Vertex (i, j) is i + n j.
Surface grid_plane(int n);
//! Icosphere: an icosahedron subdivided `level` times, projected onto the sphere.
Surface icosphere(int level, double radius);
//! m points spread evenly on a sphere (Fibonacci spiral).
Points fibonacci_sphere(Index m, const Vector3& centre, double radius);
//! n uniformly random points in the box [lo, hi]^3 (fixed seed).
Points random_box(Index n, unsigned seed, double lo, double hi);

//! Constraint residual of a fitted deformation at its constraints.
struct Residual
{
    double max_abs = 0.0, rms_abs = 0.0; //!< |d(h_i) - dh_i|, absolute
    double max_rel = 0.0, rms_rel = 0.0; //!< divided by max |dh_i|
};
Residual residual(const meshmorph::SpaceDeformation& d, const Points& handles,
                  const Points& displacements);
Json residual_json(const Residual& r);

//! Classic FFD driven "qualitatively" (paper Sec. 3.5): a designer moves the control points
//! near the handles with them. Every control point whose distance to the nearest constraint
//! is below one lattice spacing gets that constraint's displacement, every other one stays.
//! No solve: the constraints are met only approximately.
meshmorph::FfdDeformation qualitative_ffd(const meshmorph::FfdLattice& lattice,
                                          const Points& handles, const Points& displacements);

//! Mean-curvature statistics of a surface over the vertices selected by mask (NaN values, i.e.
//! border vertices, are skipped).
struct CurvatureStats
{
    Index vertices = 0;     //!< vertices counted
    double mean = 0.0;      //!< mean H
    double max = 0.0;       //!< max H
    double p99 = 0.0;       //!< 99th percentile of H
    double bending = 0.0;   //!< sum_T A_T mean(H)^2 over triangles with all 3 vertices counted
    double variation = 0.0; //!< sum_T A_T |grad H|^2 (P1 gradient), the Dirichlet energy of H
    Index local_maxima = 0; //!< vertices whose H exceeds that of every 1-ring neighbour
};
CurvatureStats curvature_stats(const Surface& s, const Eigen::VectorXd& H,
                               const std::vector<char>& mask);
Json curvature_json(const CurvatureStats& c);

//! Largest value of a non-empty range of row norms.
double max_row_norm(const Points& p);

} // namespace paper
