// SPDX-License-Identifier: GPL-3.0-or-later
// The paper's adaptivity benchmark (Sec. 3.4, Fig. 12): a plane of points whose target is the
// plane with a sharp local bump, all points constraints. Prints DoF vs max / RMS error for the
// greedy RBF (one fit per centre budget) and for DM-FFD refined by control-plane insertion in
// x and y (one fit_refined, its history), with DM-FFD on uniform lattices for reference, as a
// table and optionally as CSV. Greedy RBF rows are separate fits, each timed; the refined
// DM-FFD's total time (a fresh SVD per step) is on its last row.
// -json writes the rows and the example shapes of Fig. 12 (right): the target, the refined
// DM-FFD with at most -showDof control points and the greedy RBF with the centre count
// closest to it (heights z of the n x n grid), for benchmarks/paper/deformationBenchmarks.
//
// Usage: benchAdaptivity [-n <points per side, 41>] [-width <bump sigma, 0.05>]
//                                  [-tolerance <relative max error, 1e-3>]
//                                  [-clamping <DM-FFD SVD clamping, 1e-2>] [-csv <file>]
//                                  [-json <file>] [-showDof <900>]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"

namespace
{
using meshmorph::Index;
using meshmorph::Points;

struct Row
{
    std::string method;
    Index count = 0; // RBF centres or control points (DoF = 3 x count)
    Index rank = 0;  // DM-FFD: numerical rank of Phi after clamping; RBF: centres
    double max_error = 0.0;
    double rms_error = 0.0;
    double seconds = 0.0;
};

double now()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

} // namespace

int main(int argc, char** argv)
{
    int n = 41;
    double width = 0.05;
    double tolerance = 1e-3;
    double clamping = 1e-2;
    std::string csv, json;
    meshmorph::Index show_dof = 900;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        if (i + 1 >= argc)
        {
            std::fprintf(stderr, "Error: option %s needs a value\n", a.c_str());
            return 1;
        }
        if (a == "-n")
            n = std::atoi(argv[++i]);
        else if (a == "-width")
            width = std::atof(argv[++i]);
        else if (a == "-tolerance")
            tolerance = std::atof(argv[++i]);
        else if (a == "-clamping")
            clamping = std::atof(argv[++i]);
        else if (a == "-csv")
            csv = argv[++i];
        else if (a == "-json")
            json = argv[++i];
        else if (a == "-showDof")
            show_dof = std::atoi(argv[++i]);
        else
        {
            std::fprintf(stderr, "Error: unknown option %s\n", a.c_str());
            return 1;
        }
    }
    if (n < 4 || !(width > 0.0) || !(tolerance > 0.0))
    {
        std::fprintf(stderr, "Error: need -n >= 4, -width > 0, -tolerance > 0\n");
        return 1;
    }

    // Plane z = 0 on [0,1]^2; the bump z = 0.2 exp(-r^2 / (2 sigma^2)) centred off the lattice
    // symmetry lines at (0.62, 0.37) so that the first lattices cannot resolve it by luck.
    const Index m = Index(n) * n;
    Points x(m, 3), d = Points::Zero(m, 3);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
            const Index p = Index(i) + Index(n) * j;
            const double u = double(i) / (n - 1), v = double(j) / (n - 1);
            x.row(p) = Eigen::RowVector3d(u, v, 0.0);
            const double r2 = (u - 0.62) * (u - 0.62) + (v - 0.37) * (v - 0.37);
            d(p, 2) = 0.2 * std::exp(-r2 / (2.0 * width * width));
        }

    // Budget stops of the greedy RBF (warnings) and the planar-points note (info) are expected
    // here: errors only.
    meshmorph::log::set_level(meshmorph::log::Level::error);
    std::vector<Row> rows;
    // Example shapes (heights of the fitted plane) for -json.
    Eigen::VectorXd rbf_shape, dmffd_shape;
    Index rbf_shape_count = 0, dmffd_shape_count = 0;
    try
    {
        // Greedy RBF: fits with growing centre budgets up to the number of constraints.
        for (Index budget = 10; budget <= m; budget = budget * 3 / 2)
        {
            meshmorph::GreedySettings s;
            s.tolerance = tolerance;
            s.rms_tolerance = 0.0; // run to the budget unless the max error is met exactly
            s.max_centres = budget;
            meshmorph::GreedyRbfDeformation rbf(s);
            const double t0 = now();
            rbf.fit(x, d);
            const meshmorph::FitReport& r = rbf.report();
            rows.push_back({"greedy-rbf", r.num_centres, r.num_centres, r.max_residual,
                            r.rms_residual, now() - t0});
            if (!json.empty() && (rbf_shape_count == 0 || std::abs(r.num_centres - show_dof) <
                                                              std::abs(rbf_shape_count - show_dof)))
            {
                rbf_shape_count = r.num_centres;
                rbf_shape = meshmorph::displacements(rbf, x).col(2);
            }
            if (r.max_residual <= tolerance * r.max_displacement)
                break;
        }
        // DM-FFD on uniform k x k x 4 lattices, the reference for what adaptivity buys.
        for (int k = 4; Index(k) * k <= m; k += 2)
        {
            meshmorph::DmffdSettings s;
            s.lattice.control_points = {k, k, 4};
            s.clamping = clamping;
            meshmorph::DmffdDeformation dm(s);
            const double t0 = now();
            dm.fit(x, d);
            const meshmorph::FitReport& r = dm.report();
            rows.push_back({"dmffd-uniform", r.num_centres, r.rank, r.max_residual, r.rms_residual,
                            now() - t0});
            if (r.max_residual <= tolerance * r.max_displacement)
                break;
        }
        // DM-FFD: 4 x 4 x 4 lattice, control planes inserted in x and y (paper), until the
        // tolerance or as many DoF as constraints (the paper's stopping rule; the plane cannot
        // tell the 4 z-planes apart, the rank is nx ny, so the budget is 4 m control points).
        meshmorph::DmffdSettings s;
        s.lattice.control_points = {4, 4, 4};
        s.clamping = clamping;
        meshmorph::DmffdRefinement refinement;
        refinement.tolerance = tolerance;
        refinement.max_control_points = 4 * m;
        refinement.axes = {true, true, false};
        meshmorph::DmffdDeformation dm(s);
        const double t0 = now();
        dm.fit_refined(x, d, refinement);
        const double seconds = now() - t0;
        for (const meshmorph::DmffdRefinementStep& step : dm.refinement_history())
            rows.push_back({"dmffd-planes", step.control_points, step.rank, step.max_residual,
                            step.rms_residual, 0.0});
        rows.back().seconds = seconds; // total of all refinement steps
        if (!json.empty())
        {
            // The refinement again, stopped at the example's budget: its last lattice.
            refinement.max_control_points = show_dof;
            meshmorph::DmffdDeformation shown(s);
            shown.fit_refined(x, d, refinement);
            dmffd_shape_count = shown.refinement_history().back().control_points;
            dmffd_shape = meshmorph::displacements(shown, x).col(2);
        }
    }
    catch (const meshmorph::Error& e)
    {
        std::fprintf(stderr, "Error: %s\n", e.what());
        return 1;
    }

    double max_d = 0.0;
    for (Index i = 0; i < m; ++i)
        max_d = std::max(max_d, d.row(i).norm());
    std::printf("Adaptivity benchmark (paper Fig. 12): %d x %d plane points, bump sigma %g, "
                "max displacement %g, tolerance %g, DM-FFD clamping %g\n",
                n, n, width, max_d, tolerance, clamping);
    std::printf("%-14s %8s %8s %8s %12s %12s %12s %12s %9s\n", "method", "count", "DoF", "rank",
                "max_error", "rms_error", "max_rel", "rms_rel", "time_s");
    for (const Row& r : rows)
        std::printf("%-14s %8lld %8lld %8lld %12.4e %12.4e %12.4e %12.4e %9.3f\n", r.method.c_str(),
                    static_cast<long long>(r.count), 3LL * r.count, static_cast<long long>(r.rank),
                    r.max_error, r.rms_error, r.max_error / max_d, r.rms_error / max_d, r.seconds);
    std::printf("(count: RBF centres or DM-FFD control points; DoF = 3 x count; dmffd time_s: "
                "total of the whole refinement, on its last row)\n");
    if (!csv.empty())
    {
        std::ofstream out(csv);
        out << "method,count,dof,rank,max_error,rms_error,seconds\n";
        for (const Row& r : rows)
            out << r.method << ',' << r.count << ',' << 3 * r.count << ',' << r.rank << ','
                << r.max_error << ',' << r.rms_error << ',' << r.seconds << '\n';
        if (!out)
        {
            std::fprintf(stderr, "Error: cannot write %s\n", csv.c_str());
            return 1;
        }
    }
    if (!json.empty())
    {
        nlohmann::ordered_json j;
        j["n"] = n;
        j["width"] = width;
        j["tolerance"] = tolerance;
        j["clamping"] = clamping;
        j["constraints"] = m;
        j["maxDisplacement"] = max_d;
        j["rows"] = nlohmann::ordered_json::array();
        for (const Row& r : rows)
            j["rows"].push_back({{"method", r.method},
                                 {"count", r.count},
                                 {"rank", r.rank},
                                 {"maxError", r.max_error},
                                 {"rmsError", r.rms_error},
                                 {"seconds", r.seconds}});
        const auto heights = [](const Eigen::VectorXd& z)
        { return std::vector<double>(z.data(), z.data() + z.size()); };
        j["shapes"] = {
            {"target", heights(d.col(2))},
            {"dmffd-planes", {{"count", dmffd_shape_count}, {"z", heights(dmffd_shape)}}},
            {"greedy-rbf", {{"count", rbf_shape_count}, {"z", heights(rbf_shape)}}}};
        std::ofstream out(json);
        out << j.dump(1) << '\n';
        if (!out)
        {
            std::fprintf(stderr, "Error: cannot write %s\n", json.c_str());
            return 1;
        }
    }
    return 0;
}
