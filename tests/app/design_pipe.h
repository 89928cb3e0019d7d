// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Test helper: design studies on the tutorial pipe run through the morphMesh
//! executable (a case with its morphDict, variants' points, a linear objective J = sum w . x
//! and the gradient -sensitivity reports).
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "helpers.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"
#include "morph_run.h"
#include "shipped_pipe.h"

namespace meshmorph::design_test
{

namespace fs = std::filesystem;

//! The pipe's wall squeezed and twisted, and the inner 2x2x2 control points of a 4x4x4
//! lattice moving it sideways: 10 design variables, the body of a designVariables entry.
inline const char* wall_variables = R"dict(
    squeeze { patches (wall); type scale; origin (0 0 1); factor (0.9 0.9 1); }
    twist   { patches (wall); type rotate; origin (0 0 0); axis (0 0 1); angle 2; }
    bump
    {
        type        ffd;
        patches     (wall);
        lattice     (4 4 4);
        box         ((-0.6 -0.6 0.4) (0.6 0.6 1.6));
        directions  (x);
        confine     (1 1 1);
    }
)dict";

inline std::string read_text(const fs::path& path)
{
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

inline fs::path pipe_case(const std::string& name, const std::string& dict_body)
{
    const fs::path dir = test::scratch_dir("design_variables/" + name);
    const fs::path pipe = test::pipe_tutorial_dir();
    const io::FoamPolyMesh shipped = test::read_shipped_pipe();
    io::write_poly_mesh(shipped.mesh, io::default_poly_mesh_files(io::FoamFormat::binary), dir,
                        "constant");
    fs::create_directories(dir / "system");
    fs::copy_file(pipe / "system/controlDict", dir / "system/controlDict");
    test::write_text(dir / "system/morphDict",
                     "FoamFile { version 2.0; format ascii; class dictionary; object "
                     "morphDict; }\n" +
                         dict_body);
    return dir;
}

inline Points points_at(const fs::path& dir, const std::string& time)
{
    io::PolyMeshReadOptions o;
    o.time = io::TimeSelection::at(time);
    return io::read_poly_mesh(dir, o).mesh.points;
}

inline std::string amplitude_list(const std::vector<double>& a)
{
    std::ostringstream s;
    s.precision(17);
    s << "(";
    for (double v : a)
        s << v << " ";
    s << ")";
    return s.str();
}

//! The points of a variant (written into time 1, which is removed again).
inline Points variant_points(const fs::path& dir, const std::vector<double>& a)
{
    const test::MorphRun r =
        test::run_morph_mesh({"-case", dir.string(), "-variant", amplitude_list(a)});
    EXPECT_EQ(r.code, 0) << r.log;
    Points x = points_at(dir, "1");
    fs::remove_all(dir / "1");
    return x;
}

//! An ascii pointVectorField with `internal` and, per listed patch, fixedValue values.
inline void write_point_field(const fs::path& path, const Points& internal,
                              const std::vector<std::pair<std::string, Points>>& patches,
                              const PolyMesh& mesh)
{
    std::ostringstream s;
    s.precision(17);
    s << "FoamFile { version 2.0; format ascii; class pointVectorField; object dJdx; }\n"
      << "dimensions [0 0 0 0 0 0 0];\ninternalField nonuniform List<vector> " << internal.rows()
      << "\n(\n";
    for (Index i = 0; i < internal.rows(); ++i)
        s << "(" << internal(i, 0) << " " << internal(i, 1) << " " << internal(i, 2) << ")\n";
    s << ");\nboundaryField\n{\n";
    for (const Patch& p : mesh.patches)
    {
        s << p.name << " { type calculated; value ";
        bool listed = false;
        for (const auto& [name, values] : patches)
            if (name == p.name)
            {
                listed = true;
                s << "nonuniform List<vector> " << values.rows() << "(";
                for (Index i = 0; i < values.rows(); ++i)
                    s << "(" << values(i, 0) << " " << values(i, 1) << " " << values(i, 2) << ")";
                s << ")";
            }
        if (!listed)
            s << "uniform (0 0 0)";
        s << "; }\n";
    }
    s << "}\n";
    test::write_text(path, s.str());
}

//! J(x) = sum_i w_i . x_i with w_i smooth, distinct per point and without the pipe's
//! symmetries (which would make a squeeze's or a twist's dJ/da vanish).
inline Points weights(const Points& x0)
{
    Points w(x0.rows(), 3);
    for (Index i = 0; i < x0.rows(); ++i)
    {
        const double x = x0(i, 0), y = x0(i, 1), z = x0(i, 2);
        w.row(i) << 1.0 + x + 0.3 * z, 2.0 + y + 0.5 * x + std::sin(3 * z), 0.5 + z * x;
    }
    return w;
}

inline double objective(const Points& w, const Points& x)
{
    return (w.array() * x.array()).sum();
}

inline std::vector<double> gradient_from(const fs::path& dir, const std::string& file)
{
    const fs::path json = dir / "sens.json";
    const test::MorphRun r =
        test::run_morph_mesh({"-case", dir.string(), "-sensitivity", file, "-json", json.string()});
    EXPECT_EQ(r.code, 0) << r.log;
    const nlohmann::json j = nlohmann::json::parse(read_text(json));
    std::vector<double> g;
    for (const auto& name : j["names"])
        g.push_back(j["dJda"][name.get<std::string>()].get<double>());
    return g;
}

//! A squeeze of the pipe's wall at amplitude `amplitude` (factor 0.9 in x and y about the
//! axis per unit) moves every wall point by -0.1 amplitude (x, y, 0), exactly (the wall's end
//! rings excepted: they are also on the slipping inlet and outlet).
inline void expect_wall_squeezed(const Points& x0, const Points& xq, double amplitude)
{
    int on_wall = 0;
    for (Index i = 0; i < x0.rows(); ++i)
    {
        const double r = std::hypot(x0(i, 0), x0(i, 1));
        if (std::abs(r - 0.5) > 1e-9 || x0(i, 2) < 0.05 || x0(i, 2) > 1.95)
            continue;
        ++on_wall;
        EXPECT_NEAR(xq(i, 0) - x0(i, 0), -0.1 * amplitude * x0(i, 0), 1e-12);
        EXPECT_NEAR(xq(i, 1) - x0(i, 1), -0.1 * amplitude * x0(i, 1), 1e-12);
    }
    EXPECT_GT(on_wall, 100);
}

//! dJ/da_j (g) against central differences of J = sum w . x over variants of `dir` about a,
//! for the variables `which`: a variant is linear in a, so the difference is exact but for
//! round-off (1e-13 of J over a step of 1e-3), and 1e-6 relative bounds it with a margin.
inline void expect_central_differences(const fs::path& dir, const Points& w,
                                       const std::vector<double>& g, const std::vector<double>& a,
                                       const std::vector<std::size_t>& which)
{
    for (const std::size_t j : which)
    {
        const double h = 1e-3;
        std::vector<double> up = a, down = a;
        up[j] += h;
        down[j] -= h;
        const double fd =
            (objective(w, variant_points(dir, up)) - objective(w, variant_points(dir, down))) /
            (2 * h);
        EXPECT_NEAR(g[j], fd, 1e-6 * std::max(1.0, std::abs(fd))) << "variable " << j;
        EXPECT_GT(std::abs(fd), 1e-3) << "variable " << j << " should change J";
    }
}

} // namespace meshmorph::design_test
