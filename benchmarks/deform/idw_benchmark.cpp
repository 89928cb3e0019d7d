// SPDX-License-Identifier: GPL-3.0-or-later
// IDW on a real case: every boundary point a source, the patches matching a regex
// translated, the rest fixed; evaluation time at every mesh point and the tree's error
// against the direct sum (theta = 0) on a sample, for several opening ratios theta.
//
// Usage: benchIdw CASE [patch-regex] [sample] [theta...]
//   e.g. benchIdw build/cases/motorBike-full 'motorBike_.*' 20000 0.2 0.3 0.4 0.5
// Prints per theta: evaluate seconds, max and RMS |tree - direct| relative to the largest
// displacement.
#include <cstdlib>
#include <iostream>
#include <regex>
#include <set>

#include "meshmorph/core/stopwatch.h"
#include "meshmorph/deform/idw_deformation.h"
#include "meshmorph/io/read_poly_mesh.h"

using namespace meshmorph;

int main(int argc, char** argv)
{
    if (argc < 2)
    {
        std::cerr << "usage: benchIdw CASE [patch-regex] [sample] [theta...]\n";
        return 2;
    }
    const std::regex moving(argc > 2 ? argv[2] : "motorBike_.*");
    const Index sample = argc > 3 ? std::atoi(argv[3]) : 20000;
    std::vector<double> thetas;
    for (int i = 4; i < argc; ++i)
        thetas.push_back(std::atof(argv[i]));
    if (thetas.empty())
        thetas = {0.25, 0.4};
    const io::FoamPolyMesh foam = io::read_poly_mesh(argv[1]);
    const PolyMesh& mesh = foam.mesh;
    std::vector<Vector3> value(static_cast<std::size_t>(mesh.n_points()), Vector3::Zero());
    std::set<Index> sources;
    const Vector3 lift(0, 0, 0.0675781);
    for (const Patch& patch : mesh.patches)
        for (Index p : patch_points(mesh, patch))
        {
            const bool moves = std::regex_match(patch.name, moving);
            if (sources.insert(p).second || !moves) // shared with a fixed patch: fixed
                value[std::size_t(p)] =
                    moves && value[std::size_t(p)].isZero() ? lift : Vector3::Zero();
        }
    Points s(static_cast<Eigen::Index>(sources.size()), 3), v(s.rows(), 3);
    Eigen::Index k = 0;
    for (Index p : sources)
    {
        s.row(k) = mesh.points.row(p);
        v.row(k++) = value[std::size_t(p)].transpose();
    }
    std::cout << "case " << argv[1] << ": " << mesh.n_points() << " points, " << s.rows()
              << " sources\n";
    Points query(std::min<Index>(sample, mesh.n_points()), 3);
    for (Eigen::Index i = 0; i < query.rows(); ++i)
        query.row(i) = mesh.points.row((i * 7919) % mesh.n_points());
    IdwSettings exact_settings;
    exact_settings.theta = 0.0;
    IdwDeformation exact(exact_settings);
    exact.fit(s, v);
    Stopwatch clock;
    const Points reference = displacements(exact, query);
    std::cout << "direct sum on " << query.rows() << " points: " << clock.seconds() << " s\n";
    for (double theta : thetas)
    {
        IdwSettings settings;
        settings.theta = theta;
        IdwDeformation idw(settings);
        clock.restart();
        idw.fit(s, v);
        const double fit = clock.seconds();
        clock.restart();
        const Points all = displacements(idw, mesh.points);
        const double evaluate = clock.seconds();
        const Points approx = displacements(idw, query);
        const Eigen::VectorXd err = (approx - reference).rowwise().norm();
        std::cout << "theta " << theta << ": fit " << fit << " s, evaluate " << evaluate
                  << " s, error max " << err.maxCoeff() / lift.norm() << " rms "
                  << std::sqrt(err.squaredNorm() / double(err.size())) / lift.norm()
                  << " (relative to the lift)\n";
    }
    return 0;
}
