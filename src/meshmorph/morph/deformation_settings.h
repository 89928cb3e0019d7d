// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The settings of the space deformation a morphDict asks for: `method` and the
//! `rbf` / `idw` / `dmffd` / `ffd` sub-dictionaries, read and validated.
//!
//! ```
//! method      rbf;                 // rbf | dmffd | ffd
//! rbf   { kernel triharmonic; shape 1; polynomial linear;
//!         greedy { tolerance 1e-6; maxCentres 20000; } }   // greedy optional
//! dmffd { lattice (10 10 10); clamping 1e-2; }            // optional: bounds ((x0 y0 z0) (x1 y1
//! z1)) ffd   { lattice (4 4 4); bounds ((0 0 0) (1 1 1)); displacements ( ((1 2 3) (0 0 0.01)) );
//! }
//! ```
//! RBF without a `greedy` sub-dictionary solves directly (exact interpolation) up to
//! `direct_limit` constraints and switches to greedy centre selection above it (a dense
//! m x m system needs 8 m^2 bytes: 5000 constraints = 200 MB). DM-FFD and FFD lattices
//! enclose the whole mesh (paper Sec. 3.6) unless `bounds` is given.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/ffd_deformation.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/idw_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph::morph
{

enum class DeformationMethod
{
    rbf,
    dmffd,
    ffd,
    idw
};

//! One prescribed FFD control-point displacement.
struct ControlDisplacement
{
    std::array<int, 3> index{0, 0, 0};
    Vector3 displacement = Vector3::Zero();
};

//! Where a dictionary entry that sets the memory of a fit was given, for messages.
struct SizeEntry
{
    std::string path; //!< the dictionary file ("" when the entry is absent: a default)
    std::size_t line = 0;
    std::string name; //!< dotted keyword, e.g. "dmffd.lattice"
};

//! Everything the factory needs.
struct DeformationSettings
{
    DeformationMethod method = DeformationMethod::rbf;
    RbfSettings rbf;
    //! Set when the dictionary has `rbf { greedy { ... } }`: always greedy.
    std::optional<GreedySettings> greedy;
    //! Direct RBF up to this many constraints, greedy (GreedySettings' defaults) above.
    Index direct_limit = 5000;
    //! `method idw`, and the correction that makes a greedy RBF exact (`idw { ... }`).
    IdwSettings idw;
    //! `rbf { limit yes; }`: no point moves further than the largest prescribed displacement
    //! (CorrectedDeformation's projection; the RBF alone overshoots around a translated body).
    bool limit = true;
    DmffdSettings dmffd;
    FfdSettings ffd;
    std::vector<ControlDisplacement> ffd_displacements;
    SizeEntry dmffd_lattice{"", 0, "dmffd.lattice"};          //!< sets the DM-FFD basis size
    SizeEntry greedy_centres{"", 0, "rbf.greedy.maxCentres"}; //!< sets the greedy RBF size
};

} // namespace meshmorph::morph
