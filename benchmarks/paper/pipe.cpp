// SPDX-License-Identifier: GPL-3.0-or-later
// Paper Sec. 3.6.1 (Fig. 14): a pipe mesh (patches wall, inlet, outlet; axis z) whose wall is
// moved by the motions of benchmarks/morph/pipe_motion.py, amplitude A swept from 0 up:
//   squeeze  radially inward by A R bump(s), shift  along +x by A R bump(s),
//   s = (z - zmin) / (zmax - zmin), bump(s) = sin(pi s)^2, R the wall's largest radius;
// inlet and outlet fixed. The morph of every method is linear in the prescribed
// displacements and those are linear in A, so each method is fitted and evaluated once at
// A = 1 and the mesh at A is x + A d(x): the sweep is exact and costs one quality check per A.
// Per A: min scaled Jacobian (quality/scaled_jacobian.h) and the checkMesh counts of negative
// volumes and wrongly oriented face pyramids (quality/cell_validity.h); the mesh breaks at
// the first A where either count exceeds the undeformed mesh's (pipe_amplitudes.sh's rule
// for moveMesh), found on the grid and refined by bisection.
#include <cmath>
#include <memory>

#include "meshmorph/core/cell_shapes.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/quality/cell_validity.h"
#include "meshmorph/quality/scaled_jacobian.h"
#include "paper_common.h"
#include "sections.h"

namespace paper
{
namespace
{
using meshmorph::PolyMesh;

struct PipeMesh
{
    PolyMesh mesh;
    meshmorph::CompactList cell_faces;
    std::vector<meshmorph::CellShape> shapes;
    std::vector<Index> boundary; //!< boundary point labels
    Points unit_displacement;    //!< of the boundary points at A = 1
    double radius = 0.0;
};

PipeMesh load(const std::filesystem::path& case_dir, const std::string& motion)
{
    PipeMesh p;
    p.mesh = meshmorph::io::read_poly_mesh(case_dir).mesh;
    const PolyMesh& m = p.mesh;
    const Index wall = m.find_patch("wall");
    if (wall < 0)
        throw meshmorph::InvalidInput(case_dir.string() + ": no patch 'wall'");
    p.cell_faces = meshmorph::cell_faces(m);
    p.shapes = meshmorph::classify_cells(m, p.cell_faces);
    std::vector<char> on_wall(std::size_t(m.n_points()), 0);
    for (Index v : meshmorph::patch_points(m, m.patches[std::size_t(wall)]))
        on_wall[std::size_t(v)] = 1;
    const std::vector<char> on_boundary = meshmorph::boundary_point_mask(m);
    const double zmin = m.points.col(2).minCoeff(), zmax = m.points.col(2).maxCoeff();
    for (Index v = 0; v < m.n_points(); ++v)
    {
        if (on_boundary[std::size_t(v)])
            p.boundary.push_back(v);
        if (on_wall[std::size_t(v)])
            p.radius = std::max(p.radius, std::hypot(m.points(v, 0), m.points(v, 1)));
    }
    p.unit_displacement = Points::Zero(Index(p.boundary.size()), 3);
    for (std::size_t k = 0; k < p.boundary.size(); ++k)
    {
        const Index v = p.boundary[k];
        if (!on_wall[std::size_t(v)])
            continue; // inlet, outlet: fixed
        const double s = (m.points(v, 2) - zmin) / (zmax - zmin);
        if (s <= 1e-12 || s >= 1.0 - 1e-12)
            continue; // the wall's rims lie on the fixed ends: bump = 0 exactly
        const double mag = p.radius * std::pow(std::sin(M_PI * s), 2);
        if (motion == "squeeze")
        {
            const double r = std::hypot(m.points(v, 0), m.points(v, 1));
            p.unit_displacement.row(Index(k)) =
                Eigen::RowVector3d(-mag * m.points(v, 0) / r, -mag * m.points(v, 1) / r, 0.0);
        }
        else if (motion == "shift")
            p.unit_displacement(Index(k), 0) = mag;
        else
            throw meshmorph::InvalidInput("unknown motion '" + motion + "' (squeeze, shift)");
    }
    return p;
}

struct State
{
    meshmorph::InvalidCells invalid;
    double min_sj = 0.0;
};

State state_at(PipeMesh& p, const Points& x0, const Points& d, double a)
{
    p.mesh.points = x0 + a * d;
    const meshmorph::MeshGeometry g = meshmorph::compute_geometry(p.mesh, p.cell_faces);
    State s;
    s.invalid = meshmorph::count_invalid_cells(p.mesh, g);
    const Eigen::VectorXd sj = meshmorph::scaled_jacobian(p.mesh, p.cell_faces, p.shapes);
    s.min_sj = std::numeric_limits<double>::infinity();
    for (Index c = 0; c < sj.size(); ++c)
        if (std::isfinite(sj[c]))
            s.min_sj = std::min(s.min_sj, sj[c]);
    return s;
}

std::unique_ptr<meshmorph::SpaceDeformation> make_method(const std::string& name)
{
    if (name == "rbf")
        return std::make_unique<meshmorph::RbfDeformation>();
    if (name.rfind("dmffd-", 0) == 0)
    {
        const int l = std::stoi(name.substr(6));
        meshmorph::DmffdSettings ds; // box: the boundary's bounding box + 1% (the whole mesh)
        ds.lattice.control_points = {l, l, l};
        return std::make_unique<meshmorph::DmffdDeformation>(ds);
    }
    throw meshmorph::InvalidInput("unknown method '" + name + "'");
}

std::vector<std::string> split(const std::string& s, char sep)
{
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= s.size())
    {
        const std::size_t end = std::min(s.find(sep, start), s.size());
        if (end > start)
            out.push_back(s.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

} // namespace

Json run_pipe(const Options& o)
{
    const std::filesystem::path case_dir = o.get("case", "");
    if (case_dir.empty())
        throw meshmorph::InvalidInput("pipe: -case DIR is required");
    const std::string motion = o.get("motion", "squeeze");
    const double step = o.number("step", o.quick ? 0.05 : 0.01);
    const double amax = o.number("max", 1.0);
    const std::vector<std::string> methods =
        split(o.get("methods", "rbf,dmffd-5,dmffd-10,dmffd-15,dmffd-25"), ',');

    PipeMesh p = load(case_dir, motion);
    const Points x0 = p.mesh.points;
    const Index nb = Index(p.boundary.size());
    Points hb(nb, 3);
    for (Index k = 0; k < nb; ++k)
        hb.row(k) = x0.row(p.boundary[std::size_t(k)]);
    const meshmorph::CellShapeCounts counts = meshmorph::count_cell_shapes(p.shapes, p.cell_faces);
    const State base = state_at(p, x0, Points::Zero(x0.rows(), 3), 0.0);

    Json j = {{"case", case_dir.string()},
              {"name", o.get("name", case_dir.filename().string())},
              {"motion", motion},
              {"cells", p.mesh.n_cells},
              {"points", p.mesh.n_points()},
              {"boundaryPoints", nb},
              {"hexahedra", counts.hex},
              {"tetrahedra", counts.tet},
              {"radius", p.radius},
              {"baseMinScaledJacobian", base.min_sj},
              {"baseNegativeVolumes", base.invalid.negative_volume_cells},
              {"baseWrongPyramids", base.invalid.wrong_pyramids}};
    Json runs = Json::array();
    for (const std::string& name : methods)
    {
        const auto def = make_method(name);
        const double t0 = now();
        def->fit(hb, p.unit_displacement);
        const double fit_s = now() - t0;
        const Points d = meshmorph::displacements(*def, x0);
        const double eval_s = now() - t0 - fit_s;
        const Residual r = residual(*def, hb, p.unit_displacement);

        Json amplitudes = Json::array(), min_sj = Json::array(), neg = Json::array(),
             wrong = Json::array();
        double broken = -1.0, last_valid = 0.0;
        const int steps = int(std::lround(amax / step));
        for (int i = 0; i <= steps; ++i)
        {
            const double a = step * i;
            const State s = state_at(p, x0, d, a);
            amplitudes.push_back(a);
            min_sj.push_back(s.min_sj);
            neg.push_back(s.invalid.negative_volume_cells);
            wrong.push_back(s.invalid.wrong_pyramids);
            if (broken < 0.0)
            {
                if (s.invalid.worse_than(base.invalid))
                    broken = a;
                else
                    last_valid = a;
            }
        }
        // Bisection between the last valid grid amplitude and the first broken one.
        if (broken > 0.0)
        {
            double lo = last_valid, hi = broken;
            while (hi - lo > 1e-3)
            {
                const double mid = 0.5 * (lo + hi);
                (state_at(p, x0, d, mid).invalid.worse_than(base.invalid) ? hi : lo) = mid;
            }
            broken = hi;
        }
        p.mesh.points = x0;
        runs.push_back({{"method", name},
                        {"fitSeconds", fit_s},
                        {"evaluateSeconds", eval_s},
                        {"dof", def->report().num_centres},
                        {"rank", def->report().rank},
                        // Relative to the largest prescribed displacement: the same at every A.
                        {"residual", residual_json(r)},
                        {"breakAmplitude", broken > 0.0 ? Json(broken) : Json(nullptr)},
                        {"amplitudes", amplitudes},
                        {"minScaledJacobian", min_sj},
                        {"negativeVolumes", neg},
                        {"wrongPyramids", wrong}});
    }
    j["runs"] = runs;
    return j;
}

} // namespace paper
