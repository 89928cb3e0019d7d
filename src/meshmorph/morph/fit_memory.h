// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Up-front memory estimates of the fits a morphDict asks for, so that a lattice or
//! a centre count too large for the machine fails naming its entry before anything is
//! allocated (issue 12, resource limits).
#pragma once

#include <string>

#include "meshmorph/morph/deformation_settings.h"

namespace meshmorph::morph
{

//! Bytes an FFD lattice of `count` control points holds (its control points and their
//! displacements, n x 3 each).
double ffd_lattice_bytes(double count);

//! "1e+12" or "4096": a count that may exceed any integer type.
std::string format_count(double count);

//! The size of a fit: its bytes at least, the entry that sets it (nullptr: the mesh alone)
//! and what it is, for messages ("a lattice of 1000 control points fitted to ...").
struct FitSize
{
    double bytes = 0;
    const SizeEntry* entry = nullptr;
    std::string what;
};

//! \brief Throws when the fit's size (fit_size(), deformation_methods.h) exceeds the memory
//! this process may still allocate.
//! \throw ParseError naming the entry that sets the size (dmffd.lattice,
//! rbf.greedy.maxCentres), or InvalidInput for a size given by the mesh alone.
void check_fit_memory(const FitSize& size);

} // namespace meshmorph::morph
