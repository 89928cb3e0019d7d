// SPDX-License-Identifier: GPL-3.0-or-later
// The check before a morph on a thread of its own (serial runs) or in place (-parallel).
#include "meshmorph/morph/before_check.h"

#include "meshmorph/core/stopwatch.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/distributed_case.h"
#include "meshmorph/morph/morph_log.h"
#include "meshmorph/quality/check_mesh.h"

namespace meshmorph::morph
{

BeforeCheck::BeforeCheck(const PolyMesh& mesh, const CompactList& cell_faces,
                         const CheckMeshSettings& settings, const Decomposition& decomposition,
                         const std::filesystem::path& mesh_dir)
    : mesh_dir_(mesh_dir)
{
    if (decomposition.is_distributed())
    {
        const Stopwatch clock;
        report_ = without_cell_fields(check_morph_mesh(
            mesh, cell_faces, compute_geometry(mesh, cell_faces), settings, decomposition));
        waited_ = clock.seconds();
        warn_if_broken(*report_, mesh_dir_);
        return;
    }
    // A serial check: only the mesh and its cell faces are kept (by reference).
    running_ = std::async(
        std::launch::async,
        [&mesh, &cell_faces, settings]
        {
            require_cell_faces_of(mesh, cell_faces); // before the geometry reads the cells
            return without_cell_fields(
                check_mesh(mesh, cell_faces, compute_geometry(mesh, cell_faces), settings));
        });
}

BeforeCheck::~BeforeCheck()
{
    if (running_.valid())
        running_.wait();
}

const QualityReport& BeforeCheck::report()
{
    if (!report_)
    {
        const Stopwatch clock;
        report_ = running_.get();
        waited_ += clock.seconds();
        warn_if_broken(*report_, mesh_dir_);
    }
    return *report_;
}

QualityReport BeforeCheck::take_report()
{
    (void)report();
    QualityReport out = std::move(*report_);
    report_.reset();
    return out;
}

InvalidCells BeforeCheck::invalid()
{
    const QualityReport& r = report();
    return {r.negative_volume_cells, r.incorrectly_oriented_face_pyramids};
}

} // namespace meshmorph::morph
