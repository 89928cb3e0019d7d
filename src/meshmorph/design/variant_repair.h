// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A variant's local untangling. The linear combination x0 + sum_j a_j F_j can fold a
//! few thin cells that a one-off morph of the same motion repairs (a snappyHexMesh sliver
//! between a moving wall and a fixed one). The repair is the one-off morph's
//! (morph/local_untangle.h), applied to the variant's points: interior points near the new
//! invalid cells move; boundary points and every point a design variable prescribes (a
//! handle's) stay, so the variant stays exact. It is not linear in the amplitudes: the
//! gradient (DesignStudy::transpose_product) remains that of the linear map.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"
#include "meshmorph/mesh/mesh_geometry.h"
#include "meshmorph/morph/decomposition.h"

namespace meshmorph::design
{

//! What the repair of one variant did (tried false: it was not needed, is switched off, or
//! was skipped: `skipped` says why).
struct VariantRepair
{
    bool tried = false;
    std::string skipped;
    Index invalid_before = 0; //!< new invalid cells of the linear combination
    Index invalid_after = 0;  //!< those still invalid after the repair
    Index points_moved = 0;   //!< interior points the repair moved
    double max_move = 0.0;    //!< the largest distance it moved one
    double seconds = 0.0;
};

//! The repair of a study's variants: the targets and the points it may move, made once.
class VariantRepairer
{
public:
    //! \param mesh the study's mesh (its points are restored on return).
    //! \param x0 the set-up's points. \param prescribed per point, 1 when a design variable
    //! prescribes it. \param parts this rank's decomposition with -parallel, else null.
    VariantRepairer(PolyMesh& mesh, const CompactList& cell_faces, const Points& x0,
                    const std::vector<char>& prescribed, const morph::Decomposition* parts);

    //! \brief Repair the variant in `mesh` in place; `geometry` (compute_geometry of it on
    //! entry) is kept up to date. With more than `max_cells` cells to repair it tries
    //! nothing (`skipped` says so). Collective with -parallel (the counts are global).
    VariantRepair repair(PolyMesh& mesh, MeshGeometry& geometry, Index max_cells) const;

private:
    const CompactList& cell_faces_;
    const Points& x0_;
    const morph::Decomposition* parts_;
    std::vector<double> targets_;
    std::vector<char> movable_;
};

} // namespace meshmorph::design
