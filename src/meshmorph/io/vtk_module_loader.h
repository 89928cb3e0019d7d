// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Loads the VTK module (libmeshmorph_vtk.so, see vtk_export.h) on first use.
#pragma once

#include "meshmorph/io/vtk_export.h"

namespace meshmorph::io
{

//! The module's entry point, loaded once (thread-safe): from the build tree, else from the
//! installation's library directory. \throw IoError naming where it was looked for and why
//! it did not load.
VtkSerialise vtk_serialiser();

} // namespace meshmorph::io
