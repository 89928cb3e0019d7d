// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/morph/surface_projector.h"

#include "meshmorph/core/log.h"
#include "meshmorph/io/surface_io.h"

namespace meshmorph::morph
{

namespace fs = std::filesystem;

Points SurfaceProjector::operator()(const std::string& file, const Points& query)
{
    auto it = trees_.find(file);
    if (it == trees_.end())
    {
        fs::path path = file;
        if (path.is_relative())
            path = case_dir_ / path;
        TriangleSurface surface = io::read_surface(path);
        log::info() << "Read target surface " << path.string() << ": " << surface.n_triangles()
                    << " triangles";
        it = trees_.emplace(file, std::make_shared<SurfaceTree>(std::move(surface))).first;
    }
    return it->second->closest_points(query);
}

} // namespace meshmorph::morph
