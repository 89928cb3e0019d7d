// SPDX-License-Identifier: GPL-3.0-or-later
//! \file How a design set-up stores its variables (morphDict `designBasis`), and the choice
//! `auto` makes.
//!
//! - `fields`: a fit and a volume field per variable (design_basis.h). A variant is a sum of
//!   stored fields: the cheapest variant for a few variables, but the set-up costs a fit and
//!   an evaluation per variable and the file a field per variable.
//! - `shared`: one fit for every variable (shared_design_fit.h), chosen on a combination of
//!   their prescriptions, and per variable only its prescription (the points it moves). A
//!   variant is that fit, held, applied to its prescription: one evaluation, whatever the
//!   number of variables. The set-up costs about one morph.
//! - `auto`: `shared` above shared_above variables that move, when they constrain the same
//!   points and the case allows it (shared_design_fit.h); else `fields`.
//! The default is `fields`: the shared fit is not limited (the limit is not linear), and on
//! pitzDaily a 12-variable lattice's variant moved points 10.7 times its largest
//! prescription (max non-orthogonality 54 degrees) where the limited fields gave 1.5 times
//! (47 degrees). A study asks for `shared` or `auto` when its set-up would be too large.
#pragma once

#include <string>

namespace meshmorph::io
{
class FoamDictionary;
}

namespace meshmorph::design
{

enum class DesignStorage
{
    automatic,
    fields,
    shared
};

//! Above this many moving variables `auto` takes `shared`. On the motorBike (406,049
//! points) a field is 9.7 MB and a variant reads every field; one fit and evaluation per
//! variable made 104 variables a 50 s set-up and a 1.1 GB file, where a shared variant is
//! one held evaluation (docs/design-variables.md has the measurement).
inline constexpr int shared_above = 100;

//! morphDict `designBasis fields|shared|auto;` (default fields). \throw ParseError naming the
//! entry.
DesignStorage read_design_storage(const io::FoamDictionary& dict);

std::string to_string(DesignStorage storage);

} // namespace meshmorph::design
