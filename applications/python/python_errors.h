// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The library's exceptions as Python exceptions, with the applications' messages:
//! meshmorph.Error (a RuntimeError) and its kinds ParseError (also a ValueError: the file
//! and line are in the message), InputError (also a ValueError), IoError (also an OSError)
//! and SolverError.
#pragma once

#include <pybind11/pybind11.h>

namespace meshmorph::python
{

//! Define the exception types in `m` and translate the library's exceptions to them.
void register_errors(pybind11::module_& m);

} // namespace meshmorph::python
