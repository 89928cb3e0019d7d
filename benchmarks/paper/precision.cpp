// SPDX-License-Identifier: GPL-3.0-or-later
// Paper Sec. 3.5: how exactly each method meets its constraints. FFD moved by hand
// (qualitative_ffd), DM-FFD (least squares, Eq. 3-5) and the RBF (exact, Eq. 8) on two
// constraint sets, DM-FFD and FFD on nested lattices (4, 5, 7, 11, 19 control points per
// axis: 1, 2, 4, 8, 16 knot spans, each space contains the previous one, so the least-squares
// residual cannot grow).
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

//! The Fig. 6 constraints of Sec. 3.1: 427 points on a sphere in the unit box with a smooth
//! displacement field.
void smooth_setup(Points& h, Points& d)
{
    h = fibonacci_sphere(427, Vector3(0.5, 0.5, 0.5), 0.4);
    d.resize(h.rows(), 3);
    for (Index i = 0; i < h.rows(); ++i)
        d.row(i) = Eigen::RowVector3d(0.1 * std::sin(2 * h(i, 0) + h(i, 1)),
                                      0.05 * std::cos(3 * h(i, 1)) * h(i, 2),
                                      0.08 * std::exp(-h(i, 0) * h(i, 0)));
}

Json run_row(const std::string& scenario, const std::string& method, int lattice,
             const meshmorph::SpaceDeformation& d, const Points& h, const Points& disp)
{
    const meshmorph::FitReport& r = d.report();
    return {{"scenario", scenario},
            {"method", method},
            {"lattice", lattice},
            {"dof", method == "rbf" ? Index(r.num_centres) : Index(lattice) * lattice * lattice},
            {"rank", r.rank},
            {"constraints", h.rows()},
            {"residual", residual_json(residual(d, h, disp))}};
}

} // namespace

Json run_precision(const Options& o)
{
    const std::vector<int> lattices =
        o.quick ? std::vector<int>{4, 5, 7, 11} : std::vector<int>{4, 5, 7, 11, 19};
    Json rows = Json::array();

    // The plane of Sec. 3.3: a lifted disc next to a fixed border (a steep step).
    const PlaneSetup plane = plane_setup(o.quick ? 41 : 81, 2, o.quick ? 80 : 160, 0.15);
    for (const std::string method : {"ffd", "dmffd"})
        for (int l : lattices)
            rows.push_back(run_row("plane", method, l, *plane_method(method, l, plane),
                                   plane.position, plane.displacement));
    rows.push_back(run_row("plane", "rbf", 0, *plane_method("rbf", 0, plane), plane.position,
                           plane.displacement));

    // A smooth field at scattered points (the set-up of Sec. 3.1).
    Points h, d;
    smooth_setup(h, d);
    meshmorph::FfdBox unit;
    for (int l : lattices)
    {
        const auto ffd = qualitative_ffd(meshmorph::FfdLattice(unit, {l, l, l}), h, d);
        rows.push_back(run_row("smooth", "ffd", l, ffd, h, d));
        meshmorph::DmffdSettings ds;
        ds.lattice.control_points = {l, l, l};
        ds.lattice.box = unit;
        meshmorph::DmffdDeformation dm(ds);
        dm.fit(h, d);
        rows.push_back(run_row("smooth", "dmffd", l, dm, h, d));
    }
    meshmorph::RbfDeformation rbf;
    rbf.fit(h, d);
    rows.push_back(run_row("smooth", "rbf", 0, rbf, h, d));
    return {{"lattices", lattices}, {"runs", rows}};
}

} // namespace paper
