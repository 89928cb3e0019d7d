// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/morph/point_displacement_input.h"

#include "meshmorph/core/log.h"
#include "meshmorph/io/point_field.h"
#include "meshmorph/parallel/collective.h"

namespace meshmorph::morph
{

namespace fs = std::filesystem;

//! <time>[/<region>]/pointDisplacement of the time read (0/ when the mesh came from
//! constant/). Patches of type pointDisplacement take their boundaryField values (fixedValue /
//! calculated), else the internalField at their points; other patches' entries are not used,
//! so their disagreements do not matter here.
PointDisplacementInputs read_point_displacement(const std::filesystem::path& mesh_case,
                                                const io::FoamPolyMesh& foam,
                                                const std::string& region,
                                                const parallel::Communicator& comm)
{
    const std::string time = foam.time == "constant" ? "0" : foam.time;
    io::PointVectorField field;
    parallel::collective(comm,
                         [&]
                         {
                             field = io::read_point_vector_field(
                                 mesh_case / time / region / "pointDisplacement", foam.mesh);
                         });
    PointDisplacementInputs out{field.internal, {}};
    for (const io::PointPatchField& pf : field.patches)
        out.patches.push_back(pf.value);
    log::info() << "Read " << field.path.string();
    return out;
}

} // namespace meshmorph::morph
