// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Fits whose choices are made once and then held, so that a morph becomes a linear map
//! of its prescriptions (a design study's shared set-up, design/design_setup.h).
//!
//! The first fit() to a set of handles fits a fresh deformation (its centres, jump marks,
//! IDW tree); every later fit() to the same handles, bit for bit, refits it with those
//! choices held (SpaceDeformation::refit), unless the data are those it holds already (a
//! transpose after a variant refits nothing). A morph with slip points fits twice, without
//! and with them, so one HeldFits keeps a fitted deformation per set of handles; the
//! deformations it hands out (view()) all fit through it. Evaluating a view evaluates the
//! deformation of its last fit, as last (re)fitted: views are for one thread, used in turn.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "meshmorph/deform/space_deformation.h"

namespace meshmorph
{

class HeldFits
{
public:
    using Maker = std::function<std::unique_ptr<SpaceDeformation>()>;

    //! \param make fresh, unfitted deformations (the morph's method and settings).
    explicit HeldFits(Maker make);

    //! A deformation that fits through this object (valid while it lives).
    std::unique_ptr<SpaceDeformation> view();
    //! From now on a fit to handles not seen before is an error (InvalidInput): the choices
    //! are made, and a new set of handles would make a map that is not the one chosen.
    void freeze() { frozen_ = true; }
    //! Sets of handles fitted so far.
    std::size_t size() const { return fits_.size(); }

    //! The deformation for `handles`, fitted to `displacements` (see the file comment): its
    //! index for deformation() and refit().
    std::size_t fit(const Eigen::Ref<const Points>& handles,
                    const Eigen::Ref<const Points>& displacements);
    //! Deformation `k` refitted to `displacements` at its own handles.
    void refit(std::size_t k, const Eigen::Ref<const Points>& displacements);
    SpaceDeformation& deformation(std::size_t k) { return *fits_.at(k).deformation; }

private:
    struct Held
    {
        Points handles;
        Points displacements; //!< what the deformation was last (re)fitted to
        std::unique_ptr<SpaceDeformation> deformation;
    };
    Maker make_;
    std::vector<Held> fits_;
    bool frozen_ = false;
};

} // namespace meshmorph
