// SPDX-License-Identifier: GPL-3.0-or-later
// meshmorph.DesignStudy and meshmorph.setup_design: the design/ module (morphMesh
// -variables, -variant, -sensitivity) with numpy arrays in and out.
#include <limits>
#include <memory>
#include <mutex>
#include <optional>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "meshmorph/app/design_commands.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/design/design_setup.h"
#include "meshmorph/design/design_variant.h"
#include "meshmorph/design/valid_step.h"
#include "numpy_arrays.h"

namespace meshmorph::python
{

namespace
{

//! The Python object: the study and the last variant it evaluated (write() writes it).
struct PyStudy
{
    std::unique_ptr<design::DesignStudy> study;
    std::optional<design::VariantResult> last;
    std::unique_ptr<std::mutex> busy = std::make_unique<std::mutex>();
};

//! The library's advice names the command line (morphMesh -variables); from Python the
//! same step is meshmorph.setup_design.
std::string python_advice(std::string text)
{
    const std::string command = "morphMesh -variables";
    for (std::size_t at = text.find(command); at != std::string::npos;
         at = text.find(command, at + 1))
    {
        const std::string python = "meshmorph.setup_design(case) (" + command + ")";
        text.replace(at, command.size(), python);
        at += python.size() - 1;
    }
    return text;
}

//! DesignStudy(options), its errors' advice in Python's terms.
std::unique_ptr<design::DesignStudy> open_study(const morph::MorphOptions& o)
{
    try
    {
        return std::make_unique<design::DesignStudy>(o);
    }
    catch (const ParseError& e)
    {
        throw ParseError(e.path(), e.line(), python_advice(e.message()));
    }
    catch (const IoError& e)
    {
        throw IoError(python_advice(e.what()));
    }
    catch (const InvalidInput& e)
    {
        throw InvalidInput(python_advice(e.what()));
    }
}

std::vector<double> amplitudes_from(const PyStudy& s, const py::handle& a)
{
    std::vector<double> amplitudes = reals_from(a, "amplitudes");
    s.study->check_amplitudes(amplitudes); // count, finiteness, bounds: the CLI's messages
    return amplitudes;
}

py::object evaluate(PyStudy& s, const py::handle& a, bool back_off)
{
    const std::vector<double> amplitudes = amplitudes_from(s, a);
    const nlohmann::json report = without_gil(*s.busy,
                                              [&]
                                              {
                                                  s.last.reset(); // until the new one is whole
                                                  s.last = s.study->evaluate(amplitudes, back_off);
                                                  s.study->warn_new_check_failures(*s.last);
                                                  return app::variant_json(*s.study, *s.last);
                                              });
    return to_python(report);
}

py::array_t<double> displaced_points(PyStudy& s, const py::handle& a)
{
    const std::vector<double> amplitudes = amplitudes_from(s, a);
    Points x = without_gil(
        *s.busy, [&] { return Points(s.study->initial_points() + s.study->combine(amplitudes)); });
    return points_array(std::move(x));
}

py::object max_valid_step(PyStudy& s, const py::handle& a, const py::handle& p,
                          const py::object& limit, const py::object& max_non_orthogonality)
{
    const double theta =
        max_non_orthogonality.is_none() ? 90.0 : max_non_orthogonality.cast<double>();
    const std::vector<double> amplitudes = amplitudes_from(s, a);
    const std::vector<double> direction = reals_from(p, "direction");
    const double end =
        limit.is_none() ? std::numeric_limits<double>::infinity() : limit.cast<double>();
    const nlohmann::json report =
        without_gil(*s.busy,
                    [&]
                    {
                        s.last.reset(); // the mesh holds the step
                        const design::ValidStep r =
                            design::largest_valid_step(*s.study, amplitudes, direction, end, theta);
                        return app::valid_step_json(*s.study, amplitudes, direction, r);
                    });
    py::dict out = to_python(report);
    for (const char* key : {"step", "invalidAbove", "estimate"}) // JSON's null: unbounded
        if (out[key].is_none())
            out[key] = py::float_(std::numeric_limits<double>::infinity());
    return out;
}

py::array_t<double> transpose_product(PyStudy& s, const py::handle& g)
{
    const Index n_points = s.study->initial_points().rows(); // x0: never changes
    const py::array flat = py::array::ensure(g);
    const bool is_flat = flat && flat.ndim() == 1 && flat.size() == 3 * n_points;
    const Points dJdx = points_from(is_flat ? py::object(flat.attr("reshape")(-1, 3))
                                            : py::object(py::reinterpret_borrow<py::object>(g)),
                                    n_points, "dJ/dx");
    if (!dJdx.allFinite())
        throw InvalidInput("dJ/dx: a value is not finite (NaN or inf)");
    const std::vector<double> dJda =
        without_gil(*s.busy, [&] { return s.study->transpose_product(dJdx); });
    py::array_t<double> out(py::ssize_t(dJda.size()));
    std::copy(dJda.begin(), dJda.end(), out.mutable_data());
    return out;
}

py::object write(PyStudy& s, bool overwrite, const py::object& time)
{
    const std::optional<std::string> named =
        time.is_none() ? std::nullopt : std::optional<std::string>(py::str(time));
    const std::filesystem::path written = without_gil(
        *s.busy,
        [&]
        {
            if (!s.last)
                throw InvalidInput("no variant evaluated yet: call evaluate(a) before write()");
            if (s.last->refused)
                throw InvalidInput("the last variant was refused (" + s.last->refusal +
                                   "): nothing written (open the study with force to write "
                                   "anyway)");
            const design::DesignCase& dc = s.study->design_case();
            const std::string instance = overwrite ? dc.foam.points_instance
                                         : named   ? *named
                                                   : s.study->next_instance(dc.foam.time);
            s.study->write(*s.last, instance);
            return s.last->points_file;
        });
    return py::cast(written);
}

} // namespace

void bind_design(py::module_& m)
{
    m.def(
        "setup_design",
        [](const py::object& case_dir, const std::string& region, const py::object& time,
           bool latest_time, const py::object& dict, const std::optional<std::string>& method)
        {
            const morph::MorphOptions o =
                case_options(case_dir, region, time, latest_time, dict, method, false);
            std::optional<design::DesignSetupResult> r;
            {
                const CallsInFlight call; // (library calls that may log run without the GIL)
                const py::gil_scoped_release release;
                r = design::setup_design(o);
            }
            return to_python(app::setup_json(*r));
        },
        py::arg("case") = ".", py::kw_only(), py::arg("region") = "", py::arg("time") = py::none(),
        py::arg("latest_time") = false, py::arg("dict") = py::none(),
        py::arg("method") = py::none(),
        "morphMesh -variables: fit every design variable of the morphDict once and write the "
        "set-up (constant/designBasis); returns -variables' JSON report as a dict.");

    py::class_<PyStudy>(m, "DesignStudy",
                        "A case's design variables from its set-up (setup_design): designs "
                        "x0 + sum_j a_j F_j and gradients dJ/da without a fit.")
        .def(py::init(
                 [](const py::object& case_dir, const std::string& region, const py::object& time,
                    bool latest_time, const py::object& dict, bool force)
                 {
                     const morph::MorphOptions o =
                         case_options(case_dir, region, time, latest_time, dict, {}, force);
                     const CallsInFlight call; // (library calls that may log run without the GIL)
                     const py::gil_scoped_release release;
                     return PyStudy{open_study(o), {}, std::make_unique<std::mutex>()};
                 }),
             py::arg("case") = ".", py::kw_only(), py::arg("region") = "",
             py::arg("time") = py::none(), py::arg("latest_time") = false,
             py::arg("dict") = py::none(), py::arg("force") = false,
             "Open the set-up of a case (without time: the instance it was made on). Raises "
             "InputError for a stale set-up (run setup_design again).")
        .def_property_readonly(
            "names", [](const PyStudy& s) { return s.study->names(); },
            "The variables' names, in amplitude order.")
        .def_property_readonly(
            "bounds", [](const PyStudy& s) { return s.study->header().bounds; },
            "Per variable (lo, hi) or None.")
        .def_property_readonly(
            "setup_file", [](const PyStudy& s) { return s.study->basis_file(); },
            "The set-up file (constant[/<region>]/designBasis) the study reads.")
        .def_property_readonly(
            "initial_points",
            [](const py::object& self)
            { return points_view(self.cast<PyStudy&>().study->initial_points(), self); },
            "(n, 3) read-only view (no copy) of the set-up's points x0.")
        .def("points", &displaced_points, py::arg("a"),
             "x0 + sum_j a_j F_j as a new (n, 3) array (no check, nothing kept): the variant's "
             "points, bit for bit those evaluate(a) checks and morphMesh -variant writes "
             "unless they untangle it (their report's 'untangle').")
        .def("evaluate", &evaluate, py::arg("a"), py::kw_only(), py::arg("back_off") = false,
             "Build and check the variant a (checkMesh's metrics; new invalid cells are "
             "untangled as a one-off morph does, unless the morphDict says 'untangle no'; refused "
             "when some remain); returns morphMesh -variant's JSON report as a dict. A check "
             "the set-up's mesh passed and the variant fails is a logger warning and an entry "
             "of the report's 'newFailedChecks' (refused with 'newCheckFailures refuse'). "
             "back_off=True "
             "names the variable whose removal repairs a refused variant (one check per "
             "variable). write() writes it.")
        .def(
            "is_valid",
            [](PyStudy& s, const py::handle& a)
            {
                const std::vector<double> amplitudes = amplitudes_from(s, a);
                return without_gil(*s.busy,
                                   [&]
                                   {
                                       s.last.reset(); // the study's mesh now holds this variant
                                       return s.study->is_valid(amplitudes);
                                   });
            },
            py::arg("a"),
            "Whether the variant a has no more negative-volume cells or wrongly oriented face "
            "pyramids than x0: the cheap test for a line search (no other check, no report; "
            "the linear combination, without evaluate's untangling).")
        .def("max_valid_step", &max_valid_step, py::arg("a"), py::arg("direction"), py::kw_only(),
             py::arg("limit") = py::none(), py::arg("max_non_orthogonality") = py::none(),
             "The largest step t (up to `limit` and the variables' bounds) such that a + t * "
             "direction is valid, for a line search: each cell's volume along the direction is "
             "a cubic in t, whose first root estimates the first inversion; the step returned "
             "is confirmed by is_valid. With max_non_orthogonality (degrees), checkMesh's maximum "
             "non-orthogonality stays at or below it too. Returns morphMesh -variant -direction's "
             "JSON report as "
             "a dict (step, invalidAbove, estimate: inf when unbounded; limitedBy: "
             "'inversion', 'bounds', 'limit', 'none' or 'nonOrthogonality').")
        .def("transpose_product", &transpose_product, py::arg("dJdx"),
             "dJ/da_j = sum_i dJ/dx_i . F_j(i) for a gradient dJ/dx with respect to the points "
             "((n, 3) or flat 3n); morphMesh -sensitivity's product.")
        .def("write", &write, py::kw_only(), py::arg("overwrite") = false,
             py::arg("time") = py::none(),
             "Write the last evaluated variant atomically (to the next time after the set-up's, "
             "`time`, or with overwrite=True the mesh's instance); returns the path.");
}

} // namespace meshmorph::python
