// SPDX-License-Identifier: GPL-3.0-or-later
// The meshmorph Python module's entry point and its shared pieces (options, JSON, log).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include <atomic>
#include <chrono>
#include <thread>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/heap_reuse.h"
#include "meshmorph/core/log.h"
#include "python_errors.h"

namespace meshmorph::python
{

std::filesystem::path path_from(const py::handle& path)
{
    return py::cast<std::filesystem::path>(py::module_::import("os").attr("fspath")(path));
}

morph::MorphOptions case_options(const py::object& case_dir, const std::string& region,
                                 const py::object& time, bool latest_time, const py::object& dict,
                                 const std::optional<std::string>& method, bool force)
{
    morph::MorphOptions o;
    o.case_dir = path_from(case_dir);
    o.region = region;
    if (!time.is_none() && latest_time)
        throw py::value_error("give time or latest_time, not both");
    if (!time.is_none())
        o.time = io::TimeSelection::at(py::str(time));
    else if (latest_time)
        o.time = io::TimeSelection::latest_time();
    if (!dict.is_none())
        o.dict = path_from(dict);
    o.method = method;
    o.force = force;
    return o;
}

py::object to_python(const nlohmann::json& j)
{
    return py::module_::import("json").attr("loads")(j.dump());
}

namespace
{

std::atomic<int> calls_in_flight{0};
std::atomic<bool> closing{false};

//! One log line to Python's logging. Never throws (it runs in a destructor); drops the line
//! once the interpreter is finalising (taking the GIL then would end the thread).
void log_to_python(log::Level level, const std::string& message) noexcept
{
    if (_Py_IsFinalizing())
        return;
    try
    {
        const py::gil_scoped_acquire gil;
        const char* method = level == log::Level::error     ? "error"
                             : level == log::Level::warning ? "warning"
                             : level == log::Level::info    ? "info"
                                                            : "debug";
        try
        {
            py::module_::import("logging").attr("getLogger")("meshmorph").attr(method)(message);
        }
        catch (py::error_already_set& e)
        {
            e.discard_as_unraisable("meshmorph log");
        }
    }
    catch (...) // a line lost is better than std::terminate in a destructor
    {
    }
}

} // namespace

CallsInFlight::CallsInFlight()
{
    if (closing.load())
        throw InvalidInput("the Python interpreter is shutting down: meshmorph takes no new calls");
    ++calls_in_flight;
}

CallsInFlight::~CallsInFlight()
{
    --calls_in_flight;
}

void CallsInFlight::close_and_wait()
{
    closing.store(true);
    while (calls_in_flight.load() > 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void route_log_to_python()
{
    log::set_level(log::Level::info);
    log::set_sink(log_to_python);
    // At exit, before the interpreter finalises: no new calls, those running finish (their
    // log lines need the GIL, hence released), then the default sink again.
    py::module_::import("atexit").attr("register")(py::cpp_function(
        []
        {
            const py::gil_scoped_release release;
            CallsInFlight::close_and_wait();
            log::set_sink({});
        }));
}

} // namespace meshmorph::python

PYBIND11_MODULE(_core, m)
{
    m.doc() = "meshmorph's C++ core: cases, morphs, checks and design variables in memory "
              "(use the package meshmorph, which re-exports these).";
    meshmorph::keep_freed_blocks_in_heap(); // a variant's arrays reused, not faulted in again
    meshmorph::python::register_errors(m);
    meshmorph::python::route_log_to_python();
    meshmorph::python::bind_case(m);
    meshmorph::python::bind_design(m);
}
