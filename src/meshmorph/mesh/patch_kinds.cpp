// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/mesh/patch_kinds.h"

namespace meshmorph
{

bool is_coupled_patch(const Patch& patch)
{
    return patch.type == "cyclic" || patch.type == "cyclicSlip";
}

bool is_processor_patch(const Patch& patch)
{
    return patch.type == "processor" || is_processor_cyclic_patch(patch);
}

bool is_processor_cyclic_patch(const Patch& patch)
{
    return patch.type == "processorCyclic";
}

} // namespace meshmorph
