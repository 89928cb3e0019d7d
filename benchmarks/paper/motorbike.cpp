// SPDX-License-Identifier: GPL-3.0-or-later
// Paper Sec. 3.6.2 (Table 2) on the snappyHexMesh motorBike in place of the DrivAer car: three
// handle points on the rider (the mesh points nearest to the given positions) lifted by each
// of -lifts, every point of the outer boundary (all patches not named motorBike*) fixed, the
// bike's surface free. Fitted with the RBF (direct, exact: the paper's method; morphMesh
// would switch to its greedy selection above 5000 constraints) and DM-FFD on N^3 lattices
// spanning the constraints' bounding box (the whole domain), evaluated at every mesh point.
// The morph is linear in the lift, so each method is fitted once (to a lift of 1) and the
// mesh of lift L is x + L d(x). Each morphed mesh is written as <runs>/<method>/<L>/polyMesh/
// points (the time named by the lift) next to links to the original topology, so that
// checkMeshQuality and OpenFOAM's checkMesh judge it (deformationBenchmarks runs them);
// <runs>/original is the unmoved mesh.
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"
#include "paper_common.h"
#include "sections.h"

namespace paper
{
namespace
{
namespace fs = std::filesystem;

//! A case directory for checkMesh: constant/polyMesh holds links to the cached mesh's files
//! (a real directory, so that checkMesh's sets never land in the cache), system/ the
//! cache's fvSchemes and fvSolution and a plain controlDict (the tutorial's includes
//! function objects that are not needed here).
void make_run_case(const fs::path& cache, const fs::path& run)
{
    fs::remove_all(run);
    const fs::path poly = run / "constant" / "polyMesh";
    fs::create_directories(poly);
    for (const fs::directory_entry& e : fs::directory_iterator(cache / "constant" / "polyMesh"))
        if (e.is_regular_file())
            fs::create_symlink(fs::absolute(e.path()), poly / e.path().filename());
    fs::create_directories(run / "system");
    for (const char* f : {"fvSchemes", "fvSolution"})
        fs::copy_file(cache / "system" / f, run / "system" / f);
    std::ofstream c(run / "system" / "controlDict");
    c << "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
         "application simpleFoam;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\n"
         "endTime 1;\ndeltaT 1;\nwriteControl timeStep;\nwriteInterval 1;\n"
         "writeFormat binary;\nwritePrecision 15;\nwriteCompression off;\n"
         "timeFormat general;\ntimePrecision 6;\nrunTimeModifiable false;\n";
    if (!c)
        throw meshmorph::IoError("cannot write " + (run / "system" / "controlDict").string());
}

std::vector<Vector3> parse_positions(const std::string& text)
{
    std::vector<Vector3> out;
    std::stringstream all(text);
    std::string one;
    while (std::getline(all, one, ';'))
    {
        std::stringstream s(one);
        Vector3 p;
        if (!(s >> p.x() >> p.y() >> p.z()))
            throw meshmorph::InvalidInput("-handles: expected 'x y z;x y z;...', got '" + text +
                                          "'");
        out.push_back(p);
    }
    return out;
}

} // namespace

Json run_motorbike(const Options& o)
{
    const fs::path cache = o.get("case", "");
    const fs::path runs = o.get("runs", "");
    if (cache.empty() || runs.empty())
        throw meshmorph::InvalidInput("motorbike: -case CACHE and -runs DIR are required");
    std::vector<std::string> lifts;
    {
        std::stringstream s(o.get("lifts", "0.1,0.2,0.4"));
        std::string l;
        while (std::getline(s, l, ','))
            lifts.push_back(l);
    }
    // Top of the helmet, top of the back, right shoulder (motorBike.obj, rider-helmet and
    // rider-body groups).
    const std::vector<Vector3> wanted =
        parse_positions(o.get("handles", "0.4934 -0.0105 1.3515;0.8366 0.0333 1.2489;"
                                         "0.62 -0.2 1.15"));
    std::vector<std::string> methods;
    {
        std::stringstream s(o.get("methods", "rbf,dmffd-10,dmffd-15,dmffd-25"));
        std::string m;
        while (std::getline(s, m, ','))
            methods.push_back(m);
    }

    const meshmorph::io::FoamPolyMesh foam = meshmorph::io::read_poly_mesh(cache);
    const meshmorph::PolyMesh& mesh = foam.mesh;
    std::vector<char> fixed(std::size_t(mesh.n_points()), 0), bike(fixed.size(), 0);
    for (const meshmorph::Patch& patch : mesh.patches)
    {
        std::vector<char>& mask = patch.name.rfind("motorBike", 0) == 0 ? bike : fixed;
        for (Index v : meshmorph::patch_points(mesh, patch))
            mask[std::size_t(v)] = 1;
    }
    std::vector<Index> handles;
    Json chosen = Json::array();
    for (const Vector3& w : wanted)
    {
        Index best = -1;
        double best_d = std::numeric_limits<double>::max();
        for (Index v = 0; v < mesh.n_points(); ++v)
            if (bike[std::size_t(v)] && !fixed[std::size_t(v)])
            {
                const double d = (mesh.points.row(v).transpose() - w).norm();
                if (d < best_d)
                {
                    best_d = d;
                    best = v;
                }
            }
        if (best < 0)
            throw meshmorph::InvalidInput("motorbike: no motorBike patch points");
        handles.push_back(best);
        chosen.push_back(
            {{"wanted", {w.x(), w.y(), w.z()}},
             {"point", best},
             {"position", {mesh.points(best, 0), mesh.points(best, 1), mesh.points(best, 2)}},
             {"distance", best_d}});
    }
    Index n_fixed = 0;
    for (char f : fixed)
        n_fixed += f;
    const Index m = n_fixed + Index(handles.size());
    Points h(m, 3), d = Points::Zero(m, 3);
    Index k = 0;
    for (Index v = 0; v < mesh.n_points(); ++v)
        if (fixed[std::size_t(v)])
            h.row(k++) = mesh.points.row(v);
    for (Index v : handles)
    {
        h.row(k) = mesh.points.row(v);
        d(k++, 2) = 1.0;
    }

    make_run_case(cache, runs / "original");
    Json results = Json::array();
    for (const std::string& name : methods)
    {
        std::unique_ptr<meshmorph::SpaceDeformation> def;
        if (name == "rbf")
            def = std::make_unique<meshmorph::RbfDeformation>();
        else if (name.rfind("dmffd-", 0) == 0)
        {
            const int l = std::stoi(name.substr(6));
            meshmorph::DmffdSettings ds;
            ds.lattice.control_points = {l, l, l};
            def = std::make_unique<meshmorph::DmffdDeformation>(ds);
        }
        else
            throw meshmorph::InvalidInput("motorbike: unknown method '" + name + "'");
        const double t0 = now();
        def->fit(h, d);
        const double t1 = now();
        const Points unit = meshmorph::displacements(*def, mesh.points);
        const double t2 = now();
        make_run_case(cache, runs / name);
        double bike_max = 0.0;
        for (Index v = 0; v < mesh.n_points(); ++v)
            if (bike[std::size_t(v)])
                bike_max = std::max(bike_max, unit.row(v).norm());
        for (const std::string& lift : lifts)
        {
            const Points moved = mesh.points + std::stod(lift) * unit;
            meshmorph::io::write_points(moved, foam.points, runs / name, lift);
        }
        results.push_back({{"method", name},
                           {"fitSeconds", t1 - t0},
                           {"evaluateSeconds", t2 - t1},
                           {"dof", def->report().num_centres},
                           {"rank", def->report().rank},
                           {"condition", def->report().condition_estimate},
                           {"residual", residual_json(residual(*def, h, d))},
                           {"maxBikeDisplacementPerLift", bike_max},
                           {"case", (runs / name).string()}});
    }
    return {{"cache", cache.string()}, {"points", mesh.n_points()},
            {"cells", mesh.n_cells},   {"fixedPoints", n_fixed},
            {"handles", chosen},       {"constraints", m},
            {"lifts", lifts},          {"originalCase", (runs / "original").string()},
            {"runs", results}};
}

} // namespace paper
