// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The `designVariables` of a morphDict: named motions of unit amplitude that an
//! optimiser scales (a variant is x = x0 + sum_j a_j F_j, see design_basis.h).
//!
//! Each variable moves a set of patches (`patches (...)` with the boundary entries' types
//! translate, rotate, scale or pointDisplacement), one handle of the `handles` dictionary
//! (`handle <name>; vector (dx dy dz);`), or, for `type ffd`, expands into one variable
//! per active control point and direction of a B-spline lattice that moves the boundary
//! points of its patches (the volumetric B-spline parameterisation of OpenFOAM's adjoint
//! tools and DAFoam; named <name>.<i>.<j>.<k>.<x|y|z>; `lattice (9 5 1)` makes a lattice
//! that does not vary along z, for 2D cases). Amplitude 1 is the motion as
//! written; amplitude a is a times it. A rotation is linearised (a variant must be linear
//! in its amplitudes): amplitude a moves x by a * angle * (axis x (x - origin)), which
//! leaves the exact arc by about (a * angle)^2 / 2 of the radius.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "meshmorph/deform/bspline_basis.h"
#include "meshmorph/morph/motion.h"

namespace meshmorph::io
{
class FoamDictionary;
}

namespace meshmorph::design
{

//! A B-spline lattice (`type ffd`) whose control points are design variables.
struct DesignLattice
{
    std::string name;
    //! The cubic lattice; an axis written with 1 control point (a 2D case's normal) has 4
    //! here, and its variables move all 4 together (partition of unity: the motion is the
    //! same at every coordinate along that axis inside the box).
    FfdLattice lattice;
    std::array<int, 3> counts{4, 4, 4}; //!< as written
    //! Outer layers of control points held fixed at each side, per axis (`confine`).
    std::array<int, 3> confine{0, 0, 0};
    //! Whether control point p (linear index) belongs to the variable of (i, j, k) (counts
    //! as written).
    bool belongs(Index p, const std::array<int, 3>& ijk) const;
    std::vector<std::string> patch_keys; //!< the patches whose points it moves
    std::vector<bool> key_is_regex;
    std::size_t line = 0;
};

//! What one design variable moves at unit amplitude.
struct DesignVariable
{
    enum class Kind
    {
        patches,      //!< a motion of patches
        handle,       //!< a translation of one handle's points
        lattice_point //!< one control point of a lattice, along one axis
    };
    std::string name;
    Kind kind = Kind::patches;
    std::vector<std::string> patch_keys; //!< patches: as written (names, groups, regexes)
    std::vector<bool> key_is_regex;
    morph::Motion motion;    //!< patches: the unit motion; handle: translate (vector)
    std::string handle;      //!< handle: its name in `handles`
    std::size_t lattice = 0; //!< lattice_point: index into DesignVariables::lattices
    std::array<int, 3> control_point{0, 0, 0};       //!< lattice_point: (i, j, k) as written
    int direction = 0;                               //!< lattice_point: 0, 1, 2 for x, y, z
    std::optional<std::pair<double, double>> bounds; //!< optional (lower upper)
    std::size_t line = 0;
};

//! Every variable of a morphDict, lattices expanded, in dictionary order.
struct DesignVariables
{
    std::vector<DesignVariable> variables;
    std::vector<DesignLattice> lattices;
    std::string dict_path;

    bool empty() const { return variables.empty(); }
    Index size() const { return Index(variables.size()); }
    //! The index of `name`, or -1.
    Index find(const std::string& name) const;
    //! Whether a variable takes its motion from the case's pointDisplacement field.
    bool reads_point_displacement() const;
};

//! \brief Read `designVariables` of a parsed morphDict (empty if absent).
//! \throw ParseError naming the file, line and entry for an unknown keyword or type, a
//! `surface` variable (not linear in its amplitude), a missing selection, bad bounds, a
//! lattice without a box or with more than 10000 control points, a duplicate name.
DesignVariables read_design_variables(const io::FoamDictionary& dict);

} // namespace meshmorph::design
