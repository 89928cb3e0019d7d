// SPDX-License-Identifier: GPL-3.0-or-later
// Per-stage timings of the checker on a case: read, cell addressing, geometry, shapes,
// scaled Jacobian, check_mesh plain / -allGeometry -allTopology, and morphMesh's own checks
// (before the morph, a step's count of invalid cells, after the morph with what the check
// before and the step already have), best of N runs each.
// Usage: benchCheckMeshStages CASE [REPEATS]
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "meshmorph/core/cell_shapes.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/check_mesh.h"
#include "meshmorph/quality/scaled_jacobian.h"

using namespace meshmorph;

namespace
{

double best_of(int repeats, const std::function<void()>& work)
{
    double best = 1e300;
    for (int i = 0; i < repeats; ++i)
    {
        const auto t0 = std::chrono::steady_clock::now();
        work();
        const auto t1 = std::chrono::steady_clock::now();
        best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
    }
    return best;
}

} // namespace

int main(int argc, char* argv[])
{
    if (argc < 2)
    {
        std::cerr << "usage: benchCheckMeshStages CASE [REPEATS]\n";
        return 2;
    }
    const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
    io::FoamPolyMesh foam;
    const double t_read = best_of(repeats, [&] { foam = io::read_poly_mesh(argv[1]); });
    const PolyMesh& mesh = foam.mesh;
    CompactList cf;
    MeshGeometry g;
    std::vector<CellShape> shapes;
    const double t_cf = best_of(repeats, [&] { cf = cell_faces(mesh); });
    const double t_geom = best_of(repeats, [&] { g = compute_geometry(mesh, cf); });
    const double t_shapes = best_of(repeats, [&] { shapes = classify_cells(mesh, cf); });
    const double t_sj = best_of(repeats, [&] { (void)scaled_jacobian(mesh, cf, shapes); });
    CheckMeshSettings plain;
    CheckMeshSettings all;
    all.all_geometry = all.all_topology = true;
    const double t_plain = best_of(repeats, [&] { (void)check_mesh(mesh, cf, g, plain); });
    const double t_all = best_of(repeats, [&] { (void)check_mesh(mesh, cf, g, all); });
    // morphMesh's check after a morph, with its defaults (no -json, no -vtk): the topology
    // part and the mesh statistics are the check before's, the face pyramid errors those its
    // last step counted (count_invalid_cells, timed with the geometry as the step check).
    CheckMeshSettings before_settings;
    before_settings.scaled_jacobian = false;
    before_settings.cell_fields = false;
    const double t_before =
        best_of(repeats, [&] { (void)check_mesh(mesh, cf, g, before_settings); });
    const QualityReport before = check_mesh(mesh, cf, g, before_settings);
    std::vector<char> pyramid_errors;
    const double t_step =
        best_of(repeats, [&] { (void)count_invalid_cells(mesh, g, &pyramid_errors); });
    CheckMeshSettings after;
    after.scaled_jacobian = false;
    after.cell_fields = false;
    after.unchanged_topology = &before;
    after.face_pyramid_errors = &pyramid_errors;
    const double t_after = best_of(repeats, [&] { (void)check_mesh(mesh, cf, g, after); });
    std::cout << "case " << argv[1] << ": " << mesh.n_cells << " cells, " << mesh.n_faces()
              << " faces, best of " << repeats << "\n"
              << "  read_poly_mesh            " << t_read << " s\n"
              << "  cell_faces                " << t_cf << " s\n"
              << "  compute_geometry          " << t_geom << " s\n"
              << "  classify_cells            " << t_shapes << " s\n"
              << "  scaled_jacobian           " << t_sj << " s\n"
              << "  check_mesh plain          " << t_plain << " s (incl. shapes, jacobian)\n"
              << "  check_mesh all            " << t_all << " s (incl. shapes, jacobian)\n"
              << "  check_mesh before a morph " << t_before
              << " s (as morphMesh's check before: no scaled Jacobian, no cell fields)\n"
              << "  step check                " << t_step
              << " s (count_invalid_cells, after compute_geometry)\n"
              << "  check_mesh after a morph  " << t_after
              << " s (as morphMesh's check after: topology, statistics, pyramids reused)\n";
    return 0;
}
