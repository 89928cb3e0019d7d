// SPDX-License-Identifier: GPL-3.0-or-later
#include "python_errors.h"

#include <exception>
#include <new>

#include "meshmorph/core/exceptions.h"

namespace meshmorph::python
{

namespace py = pybind11;

namespace
{

//! A Python exception type `meshmorph.name` deriving from `bases` (a tuple), documented;
//! the module holds the reference.
py::handle new_exception(py::module_& m, const char* name, const py::tuple& bases, const char* doc)
{
    py::dict namespace_;
    namespace_["__doc__"] = doc;
    namespace_["__module__"] = "meshmorph";
    py::object type = py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(&PyType_Type))(
        name, bases, namespace_);
    m.attr(name) = type;
    return m.attr(name);
}

} // namespace

void register_errors(py::module_& m)
{
    // Handles, not objects: the module owns the types, and no reference may be dropped after
    // the interpreter has finalised.
    static py::handle error, parse_error, input_error, io_error, solver_error;
    const py::object runtime_error = py::reinterpret_borrow<py::object>(PyExc_RuntimeError);
    const py::object value_error = py::reinterpret_borrow<py::object>(PyExc_ValueError);
    const py::object os_error = py::reinterpret_borrow<py::object>(PyExc_OSError);
    error = new_exception(m, "Error", py::make_tuple(runtime_error),
                          "Any error meshmorph reports (the message is the applications').");
    parse_error = new_exception(
        m, "ParseError", py::make_tuple(py::reinterpret_borrow<py::object>(error), value_error),
        "A malformed file or dictionary; the message names file and line.");
    input_error = new_exception(
        m, "InputError", py::make_tuple(py::reinterpret_borrow<py::object>(error), value_error),
        "Input that cannot be used (wrong values, stale set-up, ...).");
    io_error = new_exception(m, "IoError",
                             py::make_tuple(py::reinterpret_borrow<py::object>(error), os_error),
                             "A file that cannot be read or written.");
    solver_error =
        new_exception(m, "SolverError", py::make_tuple(py::reinterpret_borrow<py::object>(error)),
                      "A fit that failed (singular or ill-conditioned system).");
    py::register_exception_translator(
        [](std::exception_ptr p)
        {
            try
            {
                if (p)
                    std::rethrow_exception(p);
            }
            catch (const ParseError& e)
            {
                PyErr_SetString(parse_error.ptr(), e.what());
            }
            catch (const InvalidInput& e)
            {
                PyErr_SetString(input_error.ptr(), e.what());
            }
            catch (const IoError& e)
            {
                PyErr_SetString(io_error.ptr(), e.what());
            }
            catch (const SolverError& e)
            {
                PyErr_SetString(solver_error.ptr(), e.what());
            }
            catch (const Error& e)
            {
                PyErr_SetString(error.ptr(), e.what());
            }
            catch (const std::bad_alloc&)
            {
                PyErr_SetString(PyExc_MemoryError, "meshmorph: out of memory");
            }
        });
}

} // namespace meshmorph::python
