// SPDX-License-Identifier: GPL-3.0-or-later
// Paper Sec. 3.1 (Fig. 6): the handle basis B (X = B H) precomputed for 427 constraints with
// FFD and DM-FFD on an 8^3 lattice and with the RBF; then the sizes where the choice of
// solver matters (1e4 to 1e5 constraints, 1e6 points) with the methods this project added
// for scale (greedy RBF, its IDW correction, IDW).
//
// Threads: the driver runs this section once per thread count with OMP_NUM_THREADS and
// OPENBLAS_NUM_THREADS set (OpenBLAS has its own threads), so "serial" really is one core.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/corrected_deformation.h"
#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/handle_basis.h"
#include "meshmorph/deform/idw_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"
#include "paper_common.h"
#include "sections.h"

namespace paper
{
namespace
{
using meshmorph::DmffdDeformation;
using meshmorph::FfdDeformation;
using meshmorph::FfdLattice;
using meshmorph::HandleBasis;
using meshmorph::RbfDeformation;

//! A smooth displacement field (magnitude ~0.1 on the unit box); `variant` gives a second,
//! different design for the same handles.
Points field(const Points& x, int variant)
{
    Points d(x.rows(), 3);
    const double s = variant == 0 ? 1.0 : -0.7;
    for (Index i = 0; i < x.rows(); ++i)
        d.row(i) = s * Eigen::RowVector3d(0.1 * std::sin(2 * x(i, 0) + x(i, 1) + variant),
                                          0.05 * std::cos(3 * x(i, 1)) * x(i, 2),
                                          0.08 * std::exp(-x(i, 0) * x(i, 0)));
    return d;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

//! Median seconds of `reps` runs of f.
template <class F> double timed(int reps, F&& f)
{
    std::vector<double> t;
    for (int r = 0; r < reps; ++r)
    {
        const double t0 = now();
        f();
        t.push_back(now() - t0);
    }
    return median(t);
}

double max_abs_diff(const Points& a, const Points& b)
{
    return (a - b).cwiseAbs().maxCoeff();
}

//! One method of the Fig. 6 set-up: setup (fit), basis, their sum, then the three ways to a
//! new design for the same handles: X = B H (apply), refit + evaluate, fit + evaluate.
Json fig6_method(const std::string& method, const Points& h, const Points& x, int reps,
                 const std::filesystem::path& scratch)
{
    const FfdLattice lattice(meshmorph::FfdBox{}, {8, 8, 8});
    meshmorph::DmffdSettings ds;
    ds.lattice.control_points = {8, 8, 8};
    ds.lattice.box = meshmorph::FfdBox{};
    // Handles: FFD's are its control points (B = M), the others' the 427 sphere points.
    const Points handles = method == "ffd" ? lattice.control_points() : h;
    const Points H1 = field(handles, 0), H2 = field(handles, 1);

    std::unique_ptr<RbfDeformation> rbf;
    std::unique_ptr<DmffdDeformation> dm;
    std::unique_ptr<FfdDeformation> ffd;
    HandleBasis basis;
    std::vector<double> setup, build;
    for (int r = 0; r < reps; ++r)
    {
        const double t0 = now();
        if (method == "rbf")
        {
            rbf = std::make_unique<RbfDeformation>();
            rbf->fit(handles, H1);
        }
        else if (method == "dmffd")
        {
            dm = std::make_unique<DmffdDeformation>(ds);
            dm->fit(handles, H1);
        }
        else
        {
            ffd = std::make_unique<FfdDeformation>(lattice);
            ffd->set_control_displacements(H1);
        }
        const double t1 = now();
        if (rbf)
            basis = HandleBasis::compute(*rbf, x);
        else if (dm)
            basis = HandleBasis::compute(*dm, x);
        else
            basis = HandleBasis::compute(*ffd, x);
        setup.push_back(t1 - t0);
        build.push_back(now() - t1);
    }
    const meshmorph::SpaceDeformation* fitted = ffd.get();
    if (rbf)
        fitted = rbf.get();
    else if (dm)
        fitted = dm.get();
    const meshmorph::SpaceDeformation& d = *fitted;
    // B H1 must be the fitted field at the points.
    const double scale = max_row_norm(H1);
    const double basis_error =
        max_abs_diff(basis.apply(H1), meshmorph::displacements(d, x)) / scale;

    Points X2(x.rows(), 3);
    const double apply_s = timed(std::max(reps, 3), [&] { basis.apply(H2, X2); });
    Points Y2(x.rows(), 3);
    const double refit_s = timed(reps,
                                 [&]
                                 {
                                     if (rbf)
                                         rbf->refit(H2);
                                     else if (dm)
                                         dm->refit(H2);
                                     else
                                         ffd->set_control_displacements(H2);
                                     d.evaluate(x, Y2);
                                 });
    const double refit_error = max_abs_diff(X2, Y2) / scale;
    const double fit_evaluate_s = timed(reps,
                                        [&]
                                        {
                                            if (method == "rbf")
                                            {
                                                RbfDeformation r2;
                                                r2.fit(handles, H2);
                                                r2.evaluate(x, Y2);
                                            }
                                            else if (method == "dmffd")
                                            {
                                                DmffdDeformation d2(ds);
                                                d2.fit(handles, H2);
                                                d2.evaluate(x, Y2);
                                            }
                                            else
                                            {
                                                FfdDeformation f2(lattice);
                                                f2.set_control_displacements(H2);
                                                f2.evaluate(x, Y2);
                                            }
                                        });

    // The basis in its own file format: written once, loaded per design study.
    const std::filesystem::path file = scratch / ("basis-" + method + ".mmbasis");
    const double save_s = timed(1, [&] { basis.save(file.string()); });
    HandleBasis loaded;
    const double load_s = timed(1, [&] { loaded = HandleBasis::load(file.string()); });
    const bool identical = loaded.matrix() == basis.matrix() && loaded.method() == basis.method();
    const auto file_bytes = std::filesystem::file_size(file);
    std::filesystem::remove(file);

    return {{"method", method},
            {"handles", handles.rows()},
            {"points", x.rows()},
            {"basisRows", basis.rows()},
            {"basisCols", basis.cols()},
            {"setupSeconds", median(setup)},
            {"basisSeconds", median(build)},
            {"totalSeconds", median(setup) + median(build)},
            {"applySeconds", apply_s},
            {"refitEvaluateSeconds", refit_s},
            {"fitEvaluateSeconds", fit_evaluate_s},
            {"basisVsEvaluateRel", basis_error},
            {"refitVsApplyRel", refit_error},
            {"saveSeconds", save_s},
            {"loadSeconds", load_s},
            {"fileBytes", file_bytes},
            {"loadedIdentical", identical},
            {"fitResidual", residual_json(residual(d, handles, H2))}};
}

//! Constraints of the scale study: half on a sphere (r 0.2 in the unit box) moved by a
//! smooth field, half on the box faces, fixed: a body in a far field, as in mesh morphing.
void scale_constraints(Index m, Points& h, Points& d)
{
    const Index body = m / 2, outer = m - body;
    h.resize(m, 3);
    h.topRows(body) = fibonacci_sphere(body, Vector3(0.5, 0.5, 0.5), 0.2);
    Points face = random_box(outer, 11, 0.0, 1.0);
    for (Index i = 0; i < outer; ++i)
        face(i, i % 3) = (i / 3) % 2 == 0 ? 0.0 : 1.0;
    h.bottomRows(outer) = face;
    d = Points::Zero(m, 3);
    d.topRows(body) = 0.5 * field(h.topRows(body), 0);
}

Json scale_run(const std::string& method, const Points& h, const Points& d, const Points& x,
               const std::string& skip)
{
    Json j = {{"method", method}, {"constraints", h.rows()}, {"points", x.rows()}};
    if (!skip.empty())
    {
        j["skipped"] = skip;
        return j;
    }
    std::unique_ptr<meshmorph::SpaceDeformation> def;
    if (method == "rbf")
        def = std::make_unique<RbfDeformation>();
    else if (method == "greedy+idw")
    {
        meshmorph::GreedySettings gs; // morphMesh's defaults: tolerance 1e-2, 2000 centres
        def = std::make_unique<meshmorph::CorrectedDeformation>(
            std::make_unique<meshmorph::GreedyRbfDeformation>(gs));
    }
    else if (method == "idw")
        def = std::make_unique<meshmorph::IdwDeformation>();
    else if (method == "dmffd-10")
    {
        meshmorph::DmffdSettings ds;
        ds.lattice.control_points = {10, 10, 10};
        ds.lattice.box = meshmorph::FfdBox{};
        def = std::make_unique<DmffdDeformation>(ds);
    }
    Points out(x.rows(), 3);
    double fit_s = 0.0;
    if (method == "ffd-10")
    {
        const FfdLattice lattice(meshmorph::FfdBox{}, {10, 10, 10});
        const double t0 = now();
        auto ffd = std::make_unique<FfdDeformation>(qualitative_ffd(lattice, h, d));
        fit_s = now() - t0;
        def = std::move(ffd);
    }
    else
    {
        const double t0 = now();
        def->fit(h, d);
        fit_s = now() - t0;
    }
    const double t1 = now();
    def->evaluate(x, out);
    const double eval_s = now() - t1;
    j["fitSeconds"] = fit_s;
    j["evaluateSeconds"] = eval_s;
    j["residual"] = residual_json(residual(*def, h, d));
    const meshmorph::FitReport& r = def->report();
    j["centres"] = r.num_centres;
    if (method == "greedy+idw")
    {
        j["globalResidualRel"] = r.max_displacement > 0 ? r.max_residual / r.max_displacement : 0;
        const auto& corrected = static_cast<const meshmorph::CorrectedDeformation&>(*def);
        const auto& greedy =
            static_cast<const meshmorph::GreedyRbfDeformation&>(corrected.global());
        j["greedyConverged"] = greedy.converged();
        j["greedyStoppedGrowing"] = greedy.stopped_growing();
    }
    j["maxDisplacementRatio"] = max_row_norm(out) / max_row_norm(d);
    return j;
}

} // namespace

Json run_performance(const Options& o)
{
    const Index k = Index(o.number("points", o.quick ? 5000 : 50000));
    const int reps = int(o.number("repeat", o.quick ? 1 : 3));
    const std::filesystem::path scratch = o.out.parent_path();
    Json j;
    j["threads"] = omp_get_max_threads();
    const char* blas = std::getenv("OPENBLAS_NUM_THREADS");
    j["openblasThreads"] = blas ? std::string(blas) : std::string("default");
    j["repeat"] = reps;

    // Fig. 6: 427 handles on a sphere of radius 0.4 in the unit box, k points in the box.
    const Points h = fibonacci_sphere(427, Vector3(0.5, 0.5, 0.5), 0.4);
    const Points x = random_box(k, 3, 0.0, 1.0);
    Json fig6 = Json::array();
    for (const char* method : {"ffd", "dmffd", "rbf"})
        fig6.push_back(fig6_method(method, h, x, reps, scratch));
    j["fig6"] = fig6;

    if (o.get("scale", "1") == "1")
    {
        std::vector<Index> sizes;
        Index n = 0;
        if (o.quick)
        {
            sizes = {1000, 4000};
            n = 50000;
        }
        else
        {
            sizes = {10000, 30000, 100000};
            n = 1000000;
        }
        const Index direct_limit = Index(o.number("directLimit", o.quick ? 4000 : 10000));
        const Index dmffd_limit = 30000;
        const Points xs = random_box(n, 5, 0.0, 1.0);
        Json scale = Json::array();
        for (Index m : sizes)
        {
            Points hs, ds;
            scale_constraints(m, hs, ds);
            const double gb = 8.0 * double(m) * double(m) / 1e9;
            for (const char* method : {"rbf", "greedy+idw", "idw", "dmffd-10", "ffd-10"})
            {
                std::string skip;
                if (std::string(method) == "rbf" && m > direct_limit)
                    skip = "dense m x m matrix: " + std::to_string(gb).substr(0, 5) +
                           " GB per copy (limit here: " + std::to_string(direct_limit) +
                           " constraints)";
                if (std::string(method) == "dmffd-10" && m > dmffd_limit)
                    skip = "Phi and U of the SVD: " +
                           std::to_string(16.0 * double(m) * 1000 / 1e9).substr(0, 4) +
                           " GB (limit here: 30000 constraints)";
                Json run = scale_run(method, hs, ds, xs, skip);
                run["handleBasisGB"] = 8.0 * double(n) * double(m) / 1e9;
                scale.push_back(run);
            }
        }
        j["scale"] = scale;
    }
    return j;
}

} // namespace paper
