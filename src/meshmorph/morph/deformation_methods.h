// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The one factory of space deformations: settings from a morphDict's `method` and
//! `rbf` / `dmffd` / `ffd` sub-dictionaries, and the SpaceDeformation they describe.
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

namespace meshmorph::io
{
class FoamDictionary;
}

namespace meshmorph::morph
{

enum class DeformationMethod
{
    rbf,
    dmffd,
    ffd,
    idw
};

std::string to_string(DeformationMethod method);
//! \throw InvalidInput for an unknown name (message lists rbf dmffd ffd idw).
DeformationMethod deformation_method_from_string(const std::string& name);

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
    DmffdSettings dmffd;
    FfdSettings ffd;
    std::vector<ControlDisplacement> ffd_displacements;
    SizeEntry dmffd_lattice{"", 0, "dmffd.lattice"};          //!< sets the DM-FFD basis size
    SizeEntry greedy_centres{"", 0, "rbf.greedy.maxCentres"}; //!< sets the greedy RBF size
};

//! \brief Read `method` (or `method_override`, the -method option) and the sub-dictionary of
//! the chosen method (absent: defaults). Unknown keywords and bad values are errors.
//! \throw ParseError naming the file, line and keyword; InvalidInput for a bad override.
DeformationSettings read_deformation_settings(const io::FoamDictionary& dict,
                                              const std::optional<std::string>& method_override);

//! \brief Build the deformation for `n_constraints` constraints on a mesh with points
//! `points` (n x 3; the lattice bounds of DM-FFD / FFD default to their bounding box).
//! For FFD the control displacements are already set (no fit needed).
//! \throw InvalidInput on invalid settings (lattice index out of range, ...).
std::unique_ptr<SpaceDeformation> make_deformation(const DeformationSettings& settings,
                                                   const Eigen::Ref<const Points>& points,
                                                   Index n_constraints);

//! Whether the deformation made by make_deformation() for these settings is fitted to the
//! constraints (false for FFD: its control points are prescribed).
bool needs_fit(const DeformationSettings& settings);
//! Whether the fitted field interpolates every constraint (rbf, idw) rather than fitting
//! it in the least-squares sense (dmffd) or ignoring it (ffd).
bool is_exact(const DeformationSettings& settings);

//! Short description for the log, e.g. "rbf (triharmonic, linear polynomial, direct)".
std::string describe(const DeformationSettings& settings, Index n_constraints);

} // namespace meshmorph::morph
