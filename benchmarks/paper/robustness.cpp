// SPDX-License-Identifier: GPL-3.0-or-later
// Paper Sec. 3.2: (a) DM-FFD on a 5^3 lattice deforming a sphere, the singular values clamped
// at 1e-12 .. 1e-1 (Fig. 8 compares 1e-10 and 1e-2); the artefact is measured as the largest
// deviation from the smooth (clamping 1e-2) solution and by the curvature it adds.
// (b) Surface meshes with needles, caps, non-manifold edges and vertices, disconnected
// components, duplicate vertices and zero-area triangles, deformed by FFD, DM-FFD and RBF.
#include <cmath>
#include <functional>
#include <memory>

#include "meshmorph/core/exceptions.h"
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

//! Constraints of a surface: the vertices with role 1 (handle: moved by t) or 2 (fixed).
struct Constraints
{
    std::vector<Index> vertex;
    Points position, displacement;
};

Constraints constraints_of(const Points& v, const std::vector<int>& role, const Vector3& t)
{
    Constraints c;
    for (Index i = 0; i < v.rows(); ++i)
        if (role[std::size_t(i)] != 0)
            c.vertex.push_back(i);
    const Index m = Index(c.vertex.size());
    c.position.resize(m, 3);
    c.displacement = Points::Zero(m, 3);
    for (Index k = 0; k < m; ++k)
    {
        c.position.row(k) = v.row(c.vertex[std::size_t(k)]);
        if (role[std::size_t(c.vertex[std::size_t(k)])] == 1)
            c.displacement.row(k) = t.transpose();
    }
    return c;
}

meshmorph::FfdBox cube_box(double lo, double hi)
{
    meshmorph::FfdBox box;
    box.origin = Vector3::Constant(lo);
    box.axes = (hi - lo) * Eigen::Matrix3d::Identity();
    return box;
}

Json sphere_clamping(bool quick)
{
    const Surface s = icosphere(quick ? 3 : 4, 1.0);
    const Index n = s.vertices.rows();
    std::vector<int> role(std::size_t(n), 0);
    for (Index i = 0; i < n; ++i)
        role[std::size_t(i)] = s.vertices(i, 2) > 0.6 ? 1 : s.vertices(i, 2) < -0.6 ? 2 : 0;
    const Vector3 t(0.1, 0.0, 0.3);
    const Constraints c = constraints_of(s.vertices, role, t);
    const double dmax = t.norm();
    std::vector<char> free(std::size_t(n), 0);
    for (Index i = 0; i < n; ++i)
        free[std::size_t(i)] = role[std::size_t(i)] == 0;

    meshmorph::DmffdSettings base;
    base.lattice.control_points = {5, 5, 5};
    base.lattice.box = cube_box(-1.02, 1.02); // the whole sphere, 1% margin
    const auto deform = [&](double clamping, Points& d)
    {
        meshmorph::DmffdSettings ds = base;
        ds.clamping = clamping;
        auto dm = std::make_unique<DmffdDeformation>(ds);
        dm->fit(c.position, c.displacement);
        d = meshmorph::displacements(*dm, s.vertices);
        return dm;
    };
    Points smooth;
    deform(1e-2, smooth);
    RbfDeformation rbf;
    rbf.fit(c.position, c.displacement);
    const Points d_rbf = meshmorph::displacements(rbf, s.vertices);

    Json j = {{"vertices", n},
              {"triangles", s.triangles.rows()},
              {"constraints", c.position.rows()},
              {"handleDisplacement", {t.x(), t.y(), t.z()}},
              {"lattice", 5}};
    Json rows = Json::array();
    Json shapes = Json::object();
    const auto record_shape = [&](const std::string& name, const Points& d)
    {
        const Points moved = s.vertices + d;
        const Eigen::VectorXd H = meshmorph::mean_curvature(moved, s.triangles);
        shapes[name] = {{"vertices", rows_json(moved, 5)}, {"H", vector_json(H, 4)}};
        return H;
    };
    for (double clamping : {1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-3, 1e-2, 1e-1})
    {
        Points d;
        const auto dm = deform(clamping, d);
        const Points moved = s.vertices + d;
        const Eigen::VectorXd H = meshmorph::mean_curvature(moved, s.triangles);
        const CurvatureStats cs = curvature_stats({moved, s.triangles}, H, free);
        double free_max = 0.0, dev_smooth = 0.0, dev_rbf = 0.0;
        for (Index i = 0; i < n; ++i)
        {
            dev_smooth = std::max(dev_smooth, (d.row(i) - smooth.row(i)).norm());
            dev_rbf = std::max(dev_rbf, (d.row(i) - d_rbf.row(i)).norm());
            if (free[std::size_t(i)])
                free_max = std::max(free_max, d.row(i).norm());
        }
        rows.push_back({{"clamping", clamping},
                        {"rank", dm->report().rank},
                        {"condition", dm->report().condition_estimate},
                        {"residual", residual_json(residual(*dm, c.position, c.displacement))},
                        {"maxControlRel", max_row_norm(dm->ffd().control_displacements()) / dmax},
                        {"maxFreeDisplacementRel", free_max / dmax},
                        {"deviationFromSmoothRel", dev_smooth / dmax},
                        {"deviationFromRbfRel", dev_rbf / dmax},
                        {"curvature", curvature_json(cs)}});
        if (clamping == 1e-10 || clamping == 1e-2)
            record_shape(clamping == 1e-10 ? "dmffd-1e-10" : "dmffd-1e-2", d);
    }
    const Eigen::VectorXd Hr = record_shape("rbf", d_rbf);
    j["rbfCurvature"] =
        curvature_json(curvature_stats({s.vertices + d_rbf, s.triangles}, Hr, free));
    j["rbfResidual"] = residual_json(residual(rbf, c.position, c.displacement));
    j["clamping"] = rows;
    j["triangleList"] = rows_json(s.triangles);
    j["shapes"] = shapes;
    return j;
}

//! A wavy sheet on [0,1]^2: fixed for x < 0.25, handle (moved by t) for x > 0.75.
struct Sheet
{
    Surface s;
    std::vector<int> role;
};

Sheet base_sheet(int n)
{
    Sheet sh{grid_plane(n), {}};
    for (Index i = 0; i < sh.s.vertices.rows(); ++i)
    {
        const double x = sh.s.vertices(i, 0), y = sh.s.vertices(i, 1);
        sh.s.vertices(i, 2) = 0.05 * std::sin(2 * M_PI * x) * std::sin(2 * M_PI * y);
        sh.role.push_back(x < 0.25 ? 2 : x > 0.75 ? 1 : 0);
    }
    return sh;
}

Index add_vertex(Sheet& sh, const Vector3& p, int role)
{
    const Index i = sh.s.vertices.rows();
    sh.s.vertices.conservativeResize(i + 1, 3);
    sh.s.vertices.row(i) = p.transpose();
    sh.role.push_back(role);
    return i;
}

void add_triangle(Sheet& sh, Index a, Index b, Index c)
{
    const Index t = sh.s.triangles.rows();
    sh.s.triangles.conservativeResize(t + 1, 3);
    sh.s.triangles.row(t) << a, b, c;
}

//! Adds one defect of the named kind at p (on the sheet) with the given role.
void add_defect(Sheet& sh, const std::string& kind, const Vector3& p, int role, int n)
{
    const Vector3 ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
    const double h = 1.0 / (n - 1);
    if (kind == "needle") // one edge of 1e-6, two of ~h: aspect ratio ~1e5
    {
        const Index a = add_vertex(sh, p, role), b = add_vertex(sh, p + 1e-6 * h * ex, role),
                    c = add_vertex(sh, p + h * ey, role);
        add_triangle(sh, a, b, c);
    }
    else if (kind == "cap") // an angle of ~180 degrees
    {
        const Index a = add_vertex(sh, p, role), b = add_vertex(sh, p + h * ex, role),
                    c = add_vertex(sh, p + 0.5 * h * ex + 1e-6 * h * ey, role);
        add_triangle(sh, a, b, c);
    }
    else if (kind == "nonManifoldEdge") // one edge shared by three triangles (a fin)
    {
        const Index a = add_vertex(sh, p, role), b = add_vertex(sh, p + h * ex, role);
        const Index c1 = add_vertex(sh, p + 0.5 * h * (ex + ey), role),
                    c2 = add_vertex(sh, p + 0.5 * h * (ex - ey), role),
                    c3 = add_vertex(sh, p + 0.5 * h * ex + h * ez, role);
        add_triangle(sh, a, b, c1);
        add_triangle(sh, b, a, c2);
        add_triangle(sh, a, b, c3);
    }
    else if (kind == "nonManifoldVertex") // two fans touching at one vertex (a bow tie)
    {
        const Index o = add_vertex(sh, p, role);
        const Index a = add_vertex(sh, p + h * (ex + 0.5 * ey), role),
                    b = add_vertex(sh, p + h * (ex - 0.5 * ey), role),
                    c = add_vertex(sh, p - h * (ex + 0.5 * ey), role),
                    d = add_vertex(sh, p - h * (ex - 0.5 * ey), role);
        add_triangle(sh, o, a, b);
        add_triangle(sh, o, c, d);
    }
    else if (kind == "disconnected") // a separate closed tetrahedron floating above
    {
        const Vector3 q = p + 2 * h * ez;
        const Index a = add_vertex(sh, q, role), b = add_vertex(sh, q + h * ex, role),
                    c = add_vertex(sh, q + h * ey, role), d = add_vertex(sh, q + h * ez, role);
        add_triangle(sh, a, c, b);
        add_triangle(sh, a, b, d);
        add_triangle(sh, b, c, d);
        add_triangle(sh, c, a, d);
    }
    else if (kind == "duplicateVertices") // an unwelded seam: exact copies of sheet vertices
    {
        const Index a = add_vertex(sh, p, role), b = add_vertex(sh, p + h * ex, role),
                    c = add_vertex(sh, p + h * ey, role), a2 = add_vertex(sh, p, role),
                    b2 = add_vertex(sh, p + h * ex, role);
        add_triangle(sh, a, b, c);
        add_triangle(sh, b2, a2, c);
    }
    else if (kind == "zeroArea") // collinear vertices, and a triangle repeating a vertex
    {
        const Index a = add_vertex(sh, p, role), b = add_vertex(sh, p + 0.5 * h * ex, role),
                    c = add_vertex(sh, p + h * ex, role);
        add_triangle(sh, a, b, c);
        add_triangle(sh, a, a, c);
    }
    else
        throw meshmorph::InvalidInput("unknown defect " + kind);
}

Json degenerate_surfaces(bool quick)
{
    const int n = quick ? 13 : 21;
    const std::vector<std::string> kinds = {"needle",          "cap",
                                            "nonManifoldEdge", "nonManifoldVertex",
                                            "disconnected",    "duplicateVertices",
                                            "zeroArea"};
    const Vector3 t(0.02, 0.0, 0.1);
    const double dmax = t.norm();
    const Sheet clean = base_sheet(n);
    const Index n_base = clean.s.vertices.rows();

    // The variants: each defect in the handle region and in the free region, then all at once.
    struct Variant
    {
        std::string name, region;
        Sheet sheet;
    };
    std::vector<Variant> variants;
    variants.push_back({"none", "-", clean});
    for (const std::string& kind : kinds)
        for (const auto& [region, role, x] :
             {std::tuple{"handle", 1, 0.85}, std::tuple{"free", 0, 0.5}})
        {
            Sheet sh = clean;
            add_defect(sh, kind, Vector3(x, 0.43, 0.0), role, n);
            variants.push_back({kind, region, sh});
        }
    Sheet all = clean;
    for (std::size_t k = 0; k < kinds.size(); ++k)
    {
        const double y = 0.1 + 0.8 * double(k) / double(kinds.size());
        add_defect(all, kinds[k], Vector3(0.85, y, 0.0), 1, n);
        add_defect(all, kinds[k], Vector3(0.5, y, 0.0), 0, n);
        add_defect(all, kinds[k], Vector3(0.1, y, 0.0), 2, n);
    }
    variants.push_back({"all", "all", all});

    meshmorph::FfdBox box;
    box.origin = Vector3(-0.05, -0.05, -0.5);
    box.axes = Eigen::Vector3d(1.1, 1.1, 1.0).asDiagonal();
    const std::array<int, 3> lattice{6, 6, 6};

    std::map<std::string, Points> clean_result;
    Json rows = Json::array();
    for (const Variant& v : variants)
    {
        const Constraints c = constraints_of(v.sheet.s.vertices, v.sheet.role, t);
        for (const std::string method : {"ffd", "dmffd", "rbf"})
        {
            Json r = {{"defect", v.name},
                      {"region", v.region},
                      {"method", method},
                      {"vertices", v.sheet.s.vertices.rows()},
                      {"constraints", c.position.rows()}};
            try
            {
                std::unique_ptr<meshmorph::SpaceDeformation> d;
                if (method == "ffd")
                    d = std::make_unique<meshmorph::FfdDeformation>(qualitative_ffd(
                        meshmorph::FfdLattice(box, lattice), c.position, c.displacement));
                else if (method == "dmffd")
                {
                    meshmorph::DmffdSettings ds;
                    ds.lattice.control_points = lattice;
                    ds.lattice.box = box;
                    d = std::make_unique<DmffdDeformation>(ds);
                    d->fit(c.position, c.displacement);
                }
                else
                {
                    d = std::make_unique<RbfDeformation>();
                    d->fit(c.position, c.displacement);
                }
                const Points out = meshmorph::displacements(*d, v.sheet.s.vertices);
                const Points base_out = out.topRows(n_base);
                if (v.name == "none")
                    clean_result[method] = base_out;
                const double change =
                    (base_out - clean_result[method]).rowwise().norm().maxCoeff() / dmax;
                r["ok"] = out.allFinite();
                r["residual"] = residual_json(residual(*d, c.position, c.displacement));
                r["maxDisplacementRel"] = max_row_norm(out) / dmax;
                r["changeOnCleanVerticesRel"] = change;
                r["condition"] = d->report().condition_estimate;
                r["mergedDuplicates"] = d->report().num_merged_duplicates;
            }
            catch (const meshmorph::Error& e)
            {
                r["ok"] = false;
                r["error"] = e.what();
            }
            rows.push_back(r);
        }
    }
    return {{"sheetVertices", n_base},
            {"lattice", 6},
            {"defects", kinds},
            {"handleDisplacement", {t.x(), t.y(), t.z()}},
            {"runs", rows}};
}

} // namespace

Json run_robustness(const Options& o)
{
    return {{"sphere", sphere_clamping(o.quick)}, {"surfaces", degenerate_surfaces(o.quick)}};
}

} // namespace paper
