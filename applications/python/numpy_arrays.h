// SPDX-License-Identifier: GPL-3.0-or-later
//! \file numpy <-> Eigen for the Python module. Arrays coming in are validated (dtype kind,
//! shape, finiteness is left to the library) and copied once into the library's layout;
//! arrays going out either view memory that never changes while the array lives (zero
//! copy) or own a result moved into them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "meshmorph/core/types.h"

namespace meshmorph::python
{

namespace py = pybind11;

//! \brief An (n, 3) array-like of real numbers as Points (a copy); `rows` < 0: any n.
//! \throw py::type_error (not numbers) or py::value_error (shape), naming `what`.
Points points_from(const py::handle& obj, Index rows, const std::string& what);
//! \brief A length-3 vector. \throw py::type_error, py::value_error naming `what`.
Vector3 vector_from(const py::handle& obj, const std::string& what);
//! \brief A 1-D array-like of integers as labels. \throw py::type_error, py::value_error.
std::vector<Index> labels_from(const py::handle& obj, const std::string& what);
//! \brief A 1-D array-like of real numbers. \throw py::type_error, py::value_error.
std::vector<double> reals_from(const py::handle& obj, const std::string& what);

//! A read-only (n, 3) view of `points`, which must stay unchanged while `owner` lives.
py::array_t<double> points_view(const Points& points, const py::handle& owner);
//! An (n, 3) array owning `points` (moved, no copy).
py::array_t<double> points_array(Points&& points);
//! A 1-D int64 array of labels (a copy; int64 whatever the build's label size).
py::array_t<std::int64_t> labels_array(const std::vector<Index>& labels);

} // namespace meshmorph::python
