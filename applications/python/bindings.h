// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The parts of the meshmorph Python module, each registered into the module.
#pragma once

#include <filesystem>
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

#include "meshmorph/morph/morph_result.h"

namespace meshmorph::python
{

namespace py = pybind11;

//! meshmorph.Case: a case in memory (app::MorphSession).
void bind_case(py::module_& m);
//! meshmorph.DesignStudy and meshmorph.setup_design (the design/ module).
void bind_design(py::module_& m);
//! The library's log lines to Python's logging (logger "meshmorph").
void route_log_to_python();

//! A str or os.PathLike as a path (os.fspath). \throw TypeError for anything else.
std::filesystem::path path_from(const py::handle& path);

//! The options of a case as the applications' -case, -region, -time/-latestTime, -dict,
//! -method, -force give them.
morph::MorphOptions case_options(const py::object& case_dir, const std::string& region,
                                 const py::object& time, bool latest_time, const py::object& dict,
                                 const std::optional<std::string>& method, bool force);

//! Counts the calls running without the GIL, so that the interpreter's exit can wait for
//! them (a thread still inside the library when python finalises would be ended in the
//! middle of C++ code).
class CallsInFlight
{
public:
    //! \throw meshmorph InvalidInput once the interpreter is shutting down.
    CallsInFlight();
    ~CallsInFlight();
    CallsInFlight(const CallsInFlight&) = delete;
    CallsInFlight& operator=(const CallsInFlight&) = delete;
    //! At exit: refuse new calls and wait (the caller has released the GIL) for those running.
    static void close_and_wait();
};

//! \brief Run f() with the GIL released and `busy` locked: the library's work runs while
//! other Python threads go on, and calls on one object from several threads take turns.
//! The lock is taken only without the GIL (the log sink takes the GIL), so no two threads
//! can wait for each other.
template <class F> auto without_gil(std::mutex& busy, F&& f)
{
    const CallsInFlight call;
    const py::gil_scoped_release release;
    const std::lock_guard<std::mutex> guard(busy);
    return f();
}

//! A JSON document as Python objects (dict, list, float, ...).
py::object to_python(const nlohmann::json& j);

//! The keyword arguments every opening of a case takes, for the docstrings.
inline constexpr const char* case_arguments_doc =
    "case: the case directory (default '.'); region: a region of a multi-region case; "
    "time: the time to read the mesh of (a name or number; default: the mesh the case starts "
    "from, the first time that is not a motion result, else constant, as morphMesh), "
    "latest_time: read the newest time instead; dict: the morphDict to use "
    "(relative to the case); method: override the dictionary's method (rbf, dmffd, ffd, "
    "idw); force: write results although they have new invalid cells (morphMesh -force).";

} // namespace meshmorph::python
