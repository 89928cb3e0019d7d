// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Test helper: the tutorial pipe squeezed onto a venturi-shaped STL (the motion of
//! tutorials/pipe/Allrun at any depth), as a case directory with its morphDict.
#pragma once

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>

#include "helpers.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"
#include "morph_run.h"
#include "shipped_pipe.h"

namespace meshmorph::test
{

//! An ascii STL of the pipe's wall narrowed in its middle: radius 0.5 (1 - depth b) about
//! the centre line x = offset b, with b = sin^2(pi (z - 0.5)) for z in [0.5, 1.5] and 0
//! elsewhere (the venturi of tutorials/pipe/Allrun, any depth; with an offset, bent
//! sideways).
inline std::string venturi_stl(double depth, double offset = 0.0)
{
    std::ostringstream s;
    s.precision(12);
    const double pi = std::numbers::pi;
    const auto bump = [&](double z)
    {
        if (z <= 0.5 || z >= 1.5)
            return 0.0;
        const double t = std::sin(pi * (z - 0.5));
        return t * t;
    };
    const auto radius = [&](double z) { return 0.5 * (1.0 - depth * bump(z)); };
    const auto vertex = [&](double r, double t, double z)
    {
        s << "vertex " << offset * bump(z) + r * std::cos(t) << ' ' << r * std::sin(t) << ' ' << z
          << '\n';
    };
    s << "solid venturi\n";
    const int nt = 128, nz = 110;
    for (int k = 0; k < nz; ++k)
    {
        const double za = -0.1 + 2.2 * k / nz, zb = -0.1 + 2.2 * (k + 1) / nz;
        for (int i = 0; i < nt; ++i)
        {
            const double ta = 2 * pi * i / nt, tb = 2 * pi * (i + 1) / nt;
            s << "facet normal 0 0 0\nouter loop\n";
            vertex(radius(za), ta, za), vertex(radius(za), tb, za), vertex(radius(zb), tb, zb);
            s << "endloop\nendfacet\nfacet normal 0 0 0\nouter loop\n";
            vertex(radius(za), ta, za), vertex(radius(zb), tb, zb), vertex(radius(zb), ta, zb);
            s << "endloop\nendfacet\n";
        }
    }
    s << "endsolid venturi\n";
    return s.str();
}

//! The tutorial pipe (2240 hexahedra) squeezed onto a venturi of the given depth (and
//! offset, see venturi_stl).
inline std::filesystem::path venturi_case(const std::string& name, double depth,
                                          const std::string& extra,
                                          const std::string& method = "rbf", double offset = 0.0)
{
    const std::filesystem::path dir = test::scratch_dir("morph_steps/" + name);
    const std::filesystem::path pipe = test::pipe_tutorial_dir();
    const io::FoamPolyMesh shipped = test::read_shipped_pipe();
    io::write_poly_mesh(shipped.mesh, io::default_poly_mesh_files(io::FoamFormat::binary), dir,
                        "constant");
    std::filesystem::create_directories(dir / "system");
    std::filesystem::copy_file(pipe / "system/controlDict", dir / "system/controlDict");
    test::write_text(dir / "constant/triSurface/venturi.stl", venturi_stl(depth, offset));
    test::write_text(dir / "system/morphDict",
                     "FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }\n"
                     "method " +
                         method + ";\n" + extra +
                         "boundary\n{\n    wall { type surface; file "
                         "\"constant/triSurface/venturi.stl\"; }\n"
                         "    \"(inlet|outlet)\" { type slip; }\n}\n");
    return dir;
}

} // namespace meshmorph::test
