// SPDX-License-Identifier: GPL-3.0-or-later
// benchVtkExport: cost of the shape/VTK/paper-metric stages on a real mesh.
//
// Usage: benchVtkExport [-repeat N] [-out DIR] <case>
//
// Reads <case>'s polyMesh once, then times (best of N, default 3): classify_cells,
// vtk_cells, scaled_jacobian, patch_mean_curvature (all patches), write_vtu (with a
// displacement point field and the scaled Jacobian as cell data) and write_vtp_patches, and
// prints the cell-type counts and output file sizes. If OpenFOAM's foamToVTK is on PATH,
// also times `foamToVTK -case <copy> -constant -noFunctionObjects` on a copy of the case for
// comparison (it writes legacy or XML VTK of the same mesh).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>

#include "meshmorph/core/cell_shapes.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/vtk_writer.h"
#include "meshmorph/quality/mean_curvature.h"
#include "meshmorph/quality/scaled_jacobian.h"

namespace fs = std::filesystem;
using namespace meshmorph;

namespace
{

double now()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// Process CPU seconds (all threads): robust when the machine is shared, unlike wall time.
double cpu_now()
{
    return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

double last_cpu = 0; // CPU time of the best run of the last best_of

// Best wall time of `repeat` runs; last_cpu receives that run's CPU time.
double best_of(int repeat, const std::function<void()>& f)
{
    double best = 1e300;
    for (int i = 0; i < repeat; ++i)
    {
        const double t0 = now();
        const double c0 = cpu_now();
        f();
        const double wall = now() - t0;
        if (wall < best)
        {
            best = wall;
            last_cpu = cpu_now() - c0;
        }
    }
    return best;
}

} // namespace

int main(int argc, char** argv)
{
    int repeat = 3;
    fs::path out = fs::temp_directory_path() / "benchVtkExport";
    fs::path case_dir;
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "-repeat" && i + 1 < argc)
            repeat = std::atoi(argv[++i]);
        else if (arg == "-out" && i + 1 < argc)
            out = argv[++i];
        else if (!arg.empty() && arg[0] != '-')
            case_dir = arg;
        else
        {
            std::cerr << "Usage: benchVtkExport [-repeat N] [-out DIR] <case>\n";
            return 1;
        }
    }
    if (case_dir.empty())
    {
        std::cerr << "Usage: benchVtkExport [-repeat N] [-out DIR] <case>\n";
        return 1;
    }
    try
    {
        fs::create_directories(out);
        const double t0 = now();
        const PolyMesh mesh = io::read_poly_mesh(case_dir).mesh;
        std::printf("case %s: %d points, %d faces, %d cells (read %.2f s)\n", case_dir.c_str(),
                    int(mesh.n_points()), int(mesh.n_faces()), int(mesh.n_cells), now() - t0);

        const CompactList cf = cell_faces(mesh);
        std::vector<CellShape> shapes;
        const double t_classify = best_of(repeat, [&] { shapes = classify_cells(mesh, cf); });
        const double c_classify = last_cpu;
        const CellShapeCounts counts = count_cell_shapes(shapes, cf);
        std::printf("  hex %d prism %d wedge %d pyramid %d tetWedge %d tet %d polyhedra %d\n",
                    int(counts.hex), int(counts.prism), int(counts.wedge), int(counts.pyramid),
                    int(counts.tet_wedge), int(counts.tet), int(counts.polyhedron));
        VtkCells cells;
        const double t_vtk_cells = best_of(repeat, [&] { cells = vtk_cells(mesh, cf, shapes); });
        const double c_vtk_cells = last_cpu;
        Eigen::VectorXd sj;
        const double t_sj = best_of(repeat, [&] { sj = scaled_jacobian(mesh, cf, shapes); });
        const double c_sj = last_cpu;
        Eigen::VectorXd h;
        const double t_h = best_of(repeat, [&] { h = patch_mean_curvature(mesh); });
        const double c_h = last_cpu;
        const Points displacement = 1e-3 * mesh.points;
        const double t_vtu =
            best_of(repeat,
                    [&]
                    {
                        io::write_vtu(out / "mesh.vtu", mesh, {{"displacement", displacement}},
                                      {{"scaledJacobian", sj}});
                    });
        const double c_vtu = last_cpu;
        const double t_vtp = best_of(
            repeat,
            [&] {
                io::write_vtp_patches(out / "boundary.vtp", mesh, {}, {{"meanCurvature", h}});
            });
        const double c_vtp = last_cpu;
        const auto per_cell = [&](double t) { return 1e9 * t / double(mesh.n_cells); };
        std::printf("  stage                 wall [s]   cpu [s]   cpu ns/cell\n");
        const auto row = [&](const char* name, double wall, double cpu)
        { std::printf("  %-20s %9.4f %9.4f %10.1f\n", name, wall, cpu, per_cell(cpu)); };
        row("classify_cells", t_classify, c_classify);
        row("vtk_cells", t_vtk_cells, c_vtk_cells);
        row("scaled_jacobian", t_sj, c_sj);
        row("patch_mean_curvature", t_h, c_h);
        row("write_vtu", t_vtu, c_vtu);
        row("write_vtp_patches", t_vtp, c_vtp);
        std::printf("  mesh.vtu %.1f MB, boundary.vtp %.1f MB\n",
                    double(fs::file_size(out / "mesh.vtu")) / 1e6,
                    double(fs::file_size(out / "boundary.vtp")) / 1e6);

        if (std::system("command -v foamToVTK >/dev/null 2>&1") == 0)
        {
            const fs::path copy = out / "foamToVTK_case";
            fs::remove_all(copy);
            fs::create_directories(copy / "constant");
            fs::copy(case_dir / "system", copy / "system", fs::copy_options::recursive);
            fs::copy(case_dir / "constant" / "polyMesh", copy / "constant" / "polyMesh",
                     fs::copy_options::recursive);
            const std::string cmd = "foamToVTK -case '" + copy.string() +
                                    "' -constant -noFunctionObjects > '" +
                                    (out / "log.foamToVTK").string() + "' 2>&1";
            const double t = best_of(1,
                                     [&]
                                     {
                                         if (std::system(cmd.c_str()) != 0)
                                             std::printf("  foamToVTK failed (see %s)\n",
                                                         (out / "log.foamToVTK").c_str());
                                     });
            std::printf("  foamToVTK (whole run) %8.4f s\n", t);
        }
    }
    catch (const Error& e)
    {
        std::cerr << "Error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
