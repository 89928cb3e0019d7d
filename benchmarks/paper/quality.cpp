// SPDX-License-Identifier: GPL-3.0-or-later
// Paper Sec. 3.3 (Fig. 9, 10): a plane whose border is fixed and whose centre disc is lifted;
// the same constraints fitted by DM-FFD (9^3 = 729 control points), the RBF (one kernel per
// constraint, 792 in the full run) and classic FFD moved by hand (qualitative_ffd). The
// smoothness of each result is measured by the discrete mean curvature (cotangent
// Laplace-Beltrami, quality/mean_curvature.h) of the deformed plane.
#include <cmath>
#include <memory>

#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"
#include "paper_common.h"
#include "sections.h"

namespace paper
{
namespace
{
using meshmorph::DmffdDeformation;
using meshmorph::RbfDeformation;

meshmorph::FfdBox plane_box()
{
    meshmorph::FfdBox box;
    box.origin = Vector3(-0.01, -0.01, -0.5);
    box.axes = Eigen::Vector3d(1.02, 1.02, 1.0).asDiagonal();
    return box;
}

} // namespace

PlaneSetup plane_setup(int n, int rings, Index disc, double lift)
{
    PlaneSetup p{grid_plane(n), {}, {}, {}};
    const Index nv = p.s.vertices.rows();
    p.role.assign(std::size_t(nv), 0);
    std::vector<std::pair<double, Index>> by_distance;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
            const Index v = i + Index(n) * j;
            if (std::min({i, j, n - 1 - i, n - 1 - j}) < rings)
                p.role[std::size_t(v)] = 2;
            else
                by_distance.push_back(
                    {(p.s.vertices.row(v) - Eigen::RowVector3d(0.5, 0.5, 0.0)).norm(), v});
        }
    std::sort(by_distance.begin(), by_distance.end());
    for (Index k = 0; k < disc && k < Index(by_distance.size()); ++k)
        p.role[std::size_t(by_distance[std::size_t(k)].second)] = 1;
    Index m = 0;
    for (int r : p.role)
        m += r != 0;
    p.position.resize(m, 3);
    p.displacement = Points::Zero(m, 3);
    Index k = 0;
    for (Index v = 0; v < nv; ++v)
        if (p.role[std::size_t(v)] != 0)
        {
            p.position.row(k) = p.s.vertices.row(v);
            if (p.role[std::size_t(v)] == 1)
                p.displacement(k, 2) = lift;
            ++k;
        }
    return p;
}

std::unique_ptr<meshmorph::SpaceDeformation> plane_method(const std::string& method, int lattice,
                                                          const PlaneSetup& p)
{
    if (method == "rbf")
    {
        auto r = std::make_unique<RbfDeformation>();
        r->fit(p.position, p.displacement);
        return r;
    }
    if (method == "ffd")
        return std::make_unique<meshmorph::FfdDeformation>(
            qualitative_ffd(meshmorph::FfdLattice(plane_box(), {lattice, lattice, lattice}),
                            p.position, p.displacement));
    meshmorph::DmffdSettings ds;
    ds.lattice.control_points = {lattice, lattice, lattice};
    ds.lattice.box = plane_box();
    auto d = std::make_unique<DmffdDeformation>(ds);
    d->fit(p.position, p.displacement);
    return d;
}

Json run_quality(const Options& o)
{
    // Full: 81 x 81 vertices, 2 fixed rings (632) + 160 handle vertices = 792 constraints.
    const int n = o.quick ? 41 : 81;
    const PlaneSetup p = plane_setup(n, 2, o.quick ? 80 : 160, 0.15);
    std::vector<char> free(p.role.size());
    for (std::size_t i = 0; i < free.size(); ++i)
        free[i] = p.role[i] == 0;

    Json runs = Json::array();
    struct Case
    {
        std::string method;
        int lattice;
        bool picture;
    };
    const std::vector<Case> cases = {{"dmffd", 9, true},   {"rbf", 0, true},
                                     {"ffd", 9, true},     {"dmffd", 5, false},
                                     {"dmffd", 13, false}, {"dmffd", 17, false}};
    for (const Case& c : cases)
    {
        const double t0 = now();
        const auto d = plane_method(c.method, c.lattice, p);
        const double fit_s = now() - t0;
        const Points moved = p.s.vertices + meshmorph::displacements(*d, p.s.vertices);
        const Eigen::VectorXd H = meshmorph::mean_curvature(moved, p.s.triangles);
        Json r = {{"method", c.method},
                  {"lattice", c.lattice},
                  {"dof", c.method == "rbf" ? Index(d->report().num_centres)
                                            : Index(c.lattice) * c.lattice * c.lattice},
                  {"fitSeconds", fit_s},
                  {"residual", residual_json(residual(*d, p.position, p.displacement))},
                  {"curvature", curvature_json(curvature_stats({moved, p.s.triangles}, H, free))}};
        // The centre line y = 0.5 (row j = (n - 1) / 2): the profile of Fig. 10.
        Json profile = Json::array();
        const Index j = (n - 1) / 2;
        for (int i = 0; i < n; ++i)
            profile.push_back(moved(i + Index(n) * j, 2));
        r["profileZ"] = profile;
        if (c.picture)
        {
            r["z"] = vector_json(moved.col(2), 6);
            r["H"] = vector_json(H, 5);
        }
        runs.push_back(r);
    }
    Json roles = Json::array();
    for (int r : p.role)
        roles.push_back(r);
    return {{"grid", n},
            {"constraints", p.position.rows()},
            {"handleVertices", std::count(p.role.begin(), p.role.end(), 1)},
            {"fixedVertices", std::count(p.role.begin(), p.role.end(), 2)},
            {"lift", 0.15},
            {"role", roles},
            {"runs", runs}};
}

} // namespace paper
