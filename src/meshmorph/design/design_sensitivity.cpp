// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/design/design_sensitivity.h"

#include <sstream>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/core/number_format.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/point_field.h"
#include "meshmorph/parallel/collective.h"

namespace meshmorph::design
{

namespace fs = std::filesystem;

Points read_point_sensitivity(const DesignStudy& study, const fs::path& file)
{
    const DesignCase& dc = study.design_case();
    return read_point_sensitivity(dc.foam.mesh, file.is_absolute() ? file : dc.mesh_case / file);
}

Points read_point_sensitivity(const PolyMesh& mesh, const fs::path& path)
{
    io::PointVectorField field;
    parallel::collective(
        parallel::Communicator::world(),
        [&]
        {
            try
            {
                field = io::read_point_vector_field(path, mesh, true);
            }
            catch (const ParseError& e)
            {
                if (std::string(e.what()).find("pointScalarField") == std::string::npos)
                    throw;
                throw ParseError(path.string(), 0,
                                 "a pointScalarField (a normal sensitivity such as "
                                 "pointSensNormal, by default divided by the points' "
                                 "areas) is not dJ/dx: give the pointVectorField "
                                 "pointSensVec..., written by OpenFOAM's adjoint with "
                                 "sensitivities { writeAllSurfaceFiles true; "
                                 "includeSurfaceArea true; }");
            }
        });
    Points g = field.internal;
    for (std::size_t p = 0; p < field.patches.size(); ++p)
    {
        if (!field.patches[p].value)
            continue;
        const Points& values = *field.patches[p].value;
        const std::vector<Index> points = patch_points(mesh, mesh.patches[p]);
        for (std::size_t k = 0; k < points.size(); ++k)
        {
            const Index i = points[k];
            const auto v = values.row(Eigen::Index(k));
            if (v.squaredNorm() > g.row(i).squaredNorm())
                g.row(i) = v;
        }
    }
    log::info() << "Read dJ/dx from " << field.path.string();
    return g;
}

SensitivityResult design_sensitivity(DesignStudy& study, const fs::path& file)
{
    SensitivityResult r;
    const Points g = read_point_sensitivity(study, file);
    r.input = file;
    r.names = study.names();
    r.gradient = study.transpose_product(g);
    r.nonzero_points = Index((g.rowwise().norm().array() > 0.0).count());
    const parallel::Communicator& comm = parallel::Communicator::world();
    r.nonzero_points = Index(comm.sum(std::int64_t(r.nonzero_points))); // shared points twice
    std::ostringstream text;
    text << "// dJ/da of every design variable: sum over the mesh points of dJ/dx . F_j\n"
         << "// dJ/dx from " << file.string() << " (" << r.nonzero_points
         << " points with a nonzero value)\n";
    for (std::size_t j = 0; j < r.names.size(); ++j)
        text << r.names[j] << " " << format_scalar(r.gradient[j], 17) << ";\n";
    const fs::path dir = study.design_case().case_dir / "postProcessing" / "morphMesh" /
                         study.design_case().foam.region;
    parallel::on_master(comm,
                        [&]
                        {
                            std::error_code ec;
                            fs::create_directories(dir, ec);
                            if (ec)
                                throw IoError("cannot create " + dir.string() + ": " +
                                              ec.message());
                            r.output = io::write_file_atomic(dir / "dJda", text.str());
                        });
    r.output = dir / "dJda";
    log::info() << "dJ/da (" << r.names.size() << " design variables):";
    for (std::size_t j = 0; j < r.names.size(); ++j)
        log::info() << "    " << r.names[j] << "  " << format_scalar(r.gradient[j], 8);
    log::info() << "Wrote " << r.output.string();
    return r;
}

} // namespace meshmorph::design
