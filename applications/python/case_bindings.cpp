// SPDX-License-Identifier: GPL-3.0-or-later
// meshmorph.Case: app::MorphSession with numpy arrays in and out.
#include <memory>
#include <mutex>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "meshmorph/app/exit_status.h"
#include "meshmorph/app/morph_mesh.h"
#include "meshmorph/app/morph_session.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/quality/check_mesh.h"
#include "meshmorph/quality/quality_json.h"
#include "numpy_arrays.h"

namespace meshmorph::python
{

namespace
{

//! The Python object: the session, and the snapshot of its current points that `points`
//! views (made once per change, so that a view never sees its memory change or go away).
struct PyCase
{
    std::unique_ptr<app::MorphSession> session;
    std::shared_ptr<const Points> snapshot;
    std::unique_ptr<std::mutex> busy = std::make_unique<std::mutex>();
};

py::array_t<double> current_points(PyCase& c)
{
    const std::shared_ptr<const Points> snapshot =
        without_gil(*c.busy,
                    [&]
                    {
                        if (!c.snapshot)
                            c.snapshot = std::make_shared<const Points>(c.session->points());
                        return c.snapshot;
                    });
    // The capsule shares the snapshot: the view outlives later morphs unchanged.
    // (The local copy: another thread may reset c.snapshot once the lock is released.)
    auto* keep = new std::shared_ptr<const Points>(snapshot);
    const py::capsule owner(keep,
                            [](void* p) { delete static_cast<std::shared_ptr<const Points>*>(p); });
    return points_view(*snapshot, owner);
}

morph::MotionType motion_named(const std::string& word, const std::string& patch)
{
    if (word == "fixed")
        return morph::MotionType::fixed;
    if (word == "slip")
        return morph::MotionType::slip;
    if (word == "free")
        return morph::MotionType::free;
    throw py::value_error(
        "patch '" + patch + "': '" + word +
        "' is not a motion (give fixed, slip, free, a vector or an (n, 3) array)");
}

//! patches={name: "fixed"|"slip"|"free" | (3,) translation | (n, 3) displacements}.
app::PatchPrescription patch_prescription(const std::string& name, const py::handle& value)
{
    app::PatchPrescription p;
    p.patch = name;
    if (py::isinstance<py::str>(value))
    {
        p.type = motion_named(py::cast<std::string>(value), name);
        return p;
    }
    const py::array a = py::array::ensure(value);
    if (a && a.ndim() == 1)
    {
        p.type = morph::MotionType::translate;
        p.vector = vector_from(value, "patch '" + name + "'"); // finiteness: MorphSession
        return p;
    }
    p.type = morph::MotionType::point_displacement;
    p.values = points_from(value, -1, "patch '" + name + "'");
    return p;
}

//! points={name: (labels, (n, 3) displacements)}.
app::PointSetPrescription point_set(const std::string& name, const py::handle& value)
{
    const std::string what = "point set '" + name + "'";
    if (!py::isinstance<py::tuple>(value) && !py::isinstance<py::list>(value))
        throw py::type_error(what + ": expected (labels, displacements)");
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(value);
    if (pair.size() != 2)
        throw py::type_error(what + ": expected (labels, displacements)");
    app::PointSetPrescription s;
    s.name = name;
    s.labels = labels_from(pair[0], what + " labels");
    s.displacements = points_from(pair[1], Index(s.labels.size()), what + " displacements");
    return s;
}

//! The entries of a {name: value} argument, refusing anything else with a TypeError.
std::vector<std::pair<std::string, py::object>> named_entries(const py::object& table,
                                                              const char* argument)
{
    if (!py::isinstance<py::dict>(table))
        throw py::type_error(std::string(argument) + ": expected a dict {name: value}");
    std::vector<std::pair<std::string, py::object>> entries; // owned: conversions run Python
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(table))
    {
        if (!py::isinstance<py::str>(key))
            throw py::type_error(std::string(argument) + ": names must be strings");
        entries.emplace_back(py::cast<std::string>(key), py::reinterpret_borrow<py::object>(value));
    }
    return entries;
}

app::Prescriptions prescriptions_from(const py::object& patches, const py::object& points)
{
    app::Prescriptions p;
    if (!patches.is_none())
        for (const auto& [name, value] : named_entries(patches, "patches"))
            p.patches.push_back(patch_prescription(name, value));
    if (!points.is_none())
        for (const auto& [name, value] : named_entries(points, "points"))
            p.point_sets.push_back(point_set(name, value));
    return p;
}

//! morphMesh's JSON document of a result (made under the object's lock).
std::string morph_json(const morph::MorphResult& r)
{
    return app::morph_json(r, r.refused ? app::exit_refused : app::exit_ok);
}

py::object check_report(PyCase& c, bool all_geometry, bool all_topology, bool scaled_jacobian)
{
    CheckMeshSettings settings;
    settings.all_geometry = all_geometry;
    settings.all_topology = all_topology;
    settings.scaled_jacobian = scaled_jacobian;
    const QualityReport report = without_gil(*c.busy, [&] { return c.session->check(settings); });
    nlohmann::json j = quality_json(report);
    j["case"] = c.session->case_dir().string();
    j["time"] = c.session->foam().time;
    j["region"] = c.session->options().region;
    return to_python(j);
}

py::dict patch_table(const PolyMesh& mesh)
{
    py::dict table;
    for (const Patch& p : mesh.patches)
    {
        py::dict d;
        d["type"] = p.type;
        d["startFace"] = p.start_face;
        d["nFaces"] = p.n_faces;
        d["inGroups"] = p.in_groups;
        table[py::str(p.name)] = d;
    }
    return table;
}

py::dict zone_table(const std::vector<Zone>& zones)
{
    py::dict table;
    for (const Zone& z : zones)
        table[py::str(z.name)] = labels_array(z.labels);
    return table;
}

} // namespace

void bind_case(py::module_& m)
{
    static const std::string case_doc =
        std::string("Read the mesh of a case. ") + case_arguments_doc +
        " scaled_jacobian: morph reports include minScaledJacobian before and after, as "
        "morphMesh -json's do (it costs as much as the checks).";
    py::class_<PyCase>(m, "Case",
                       "An OpenFOAM case's mesh in memory, morphed, checked and written any "
                       "number of times. Every morph starts from the mesh as read.")
        .def(py::init(
                 [](const py::object& case_dir, const std::string& region, const py::object& time,
                    bool latest_time, const py::object& dict,
                    const std::optional<std::string>& method, bool force, bool scaled_jacobian)
                 {
                     morph::MorphOptions o =
                         case_options(case_dir, region, time, latest_time, dict, method, force);
                     o.scaled_jacobian = scaled_jacobian;
                     const CallsInFlight call; // (library calls that may log run without the GIL)
                     const py::gil_scoped_release release;
                     return PyCase{std::make_unique<app::MorphSession>(o), nullptr,
                                   std::make_unique<std::mutex>()};
                 }),
             py::arg("case") = ".", py::kw_only(), py::arg("region") = "",
             py::arg("time") = py::none(), py::arg("latest_time") = false,
             py::arg("dict") = py::none(), py::arg("method") = py::none(), py::arg("force") = false,
             py::arg("scaled_jacobian") = false, case_doc.c_str())
        .def_property_readonly(
            "case_dir", [](const PyCase& c) { return c.session->case_dir(); },
            "The case directory.")
        .def_property_readonly(
            "region", [](const PyCase& c) { return c.session->options().region; },
            "The region ('' for the default region).")
        .def_property_readonly(
            "time", [](const PyCase& c) { return c.session->foam().time; },
            "The time the mesh was read at.")
        .def_property_readonly(
            "instance", [](const PyCase& c) { return c.session->foam().points_instance; },
            "The instance the points were read from.")
        .def_property_readonly(
            "n_points", [](const PyCase& c) { return c.session->mesh().n_points(); },
            "Number of points.")
        .def_property_readonly(
            "n_faces", [](const PyCase& c) { return c.session->mesh().n_faces(); },
            "Number of faces.")
        .def_property_readonly(
            "n_cells", [](const PyCase& c) { return c.session->mesh().n_cells; },
            "Number of cells.")
        .def_property_readonly(
            "initial_points",
            [](const py::object& self)
            { return points_view(self.cast<PyCase&>().session->initial_points(), self); },
            "(n, 3) read-only view (no copy) of the points as read, which every morph starts from.")
        .def_property_readonly(
            "points", [](PyCase& c) { return current_points(c); },
            "(n, 3) read-only view of the current points. The first access after a change "
            "copies them once; the view stays valid (and unchanged) after later morphs.")
        .def(
            "set_points",
            [](PyCase& c, const py::object& points)
            {
                Points p = points_from(points, c.session->mesh().n_points(), "points");
                without_gil(*c.busy,
                            [&]
                            {
                                c.session->set_points(std::move(p));
                                c.snapshot.reset();
                            });
            },
            py::arg("points"), "Replace the current points ((n, 3), copied).")
        .def(
            "reset",
            [](PyCase& c)
            {
                without_gil(*c.busy,
                            [&]
                            {
                                c.session->reset();
                                c.snapshot.reset();
                            });
            },
            "Back to the points as read.")
        .def_property_readonly(
            "patches", [](const PyCase& c) { return patch_table(c.session->mesh()); },
            "{name: {type, startFace, nFaces, inGroups}} in mesh order.")
        .def(
            "patch_points",
            [](const PyCase& c, const std::string& name)
            {
                const PolyMesh& mesh = c.session->mesh();
                const Index k = mesh.find_patch(name);
                if (k < 0)
                    throw InvalidInput("no patch '" + name + "' in the mesh");
                return labels_array(patch_points(mesh, mesh.patches[std::size_t(k)]));
            },
            py::arg("patch"),
            "The patch's point labels in OpenFOAM's patch-local order (the order of the rows "
            "of a patch's displacements in morph(patches=...)); a copy.")
        .def_property_readonly(
            "point_zones",
            [](const PyCase& c) { return zone_table(c.session->mesh().point_zones); },
            "{name: labels} (copies).")
        .def_property_readonly(
            "face_zones", [](const PyCase& c) { return zone_table(c.session->mesh().face_zones); },
            "{name: labels} (copies).")
        .def_property_readonly(
            "cell_zones", [](const PyCase& c) { return zone_table(c.session->mesh().cell_zones); },
            "{name: labels} (copies).")
        .def(
            "morph",
            [](PyCase& c, const py::object& dict, const py::object& patches,
               const py::object& points)
            {
                const bool given = !patches.is_none() || !points.is_none();
                if (given && !dict.is_none())
                    throw py::value_error("give dict or patches/points, not both");
                std::optional<std::filesystem::path> dict_path;
                if (!dict.is_none())
                    dict_path = path_from(dict);
                const app::Prescriptions p =
                    given ? prescriptions_from(patches, points) : app::Prescriptions{};
                const std::string report =
                    without_gil(*c.busy,
                                [&]
                                {
                                    c.snapshot.reset();
                                    return morph_json(given ? c.session->morph(p)
                                                            : c.session->morph(dict_path));
                                });
                return to_python(nlohmann::json::parse(report));
            },
            py::arg("dict") = py::none(), py::kw_only(), py::arg("patches") = py::none(),
            py::arg("points") = py::none(),
            "Morph from the mesh as read, in memory, and return morphMesh's JSON report as a "
            "dict ('refused' says whether it created invalid cells).\n"
            "  morph(): the morphDict; morph('system/morphDict.v2'): another dictionary;\n"
            "  morph(patches={'wing': d}, points={'tip': (labels, d)}): prescribed values, "
            "where a patch's value is 'fixed', 'slip', 'free', a translation (3,) or "
            "(nPatchPoints, 3) displacements in patch_points order, and a point set's "
            "displacements override the patches', like morphDict handles. The morphDict, if "
            "the case has one, gives the method and the patches not named (else fixed).")
        .def(
            "check",
            [](PyCase& c, bool all_geometry, bool all_topology, bool scaled_jacobian)
            { return check_report(c, all_geometry, all_topology, scaled_jacobian); },
            py::kw_only(), py::arg("all_geometry") = false, py::arg("all_topology") = false,
            py::arg("scaled_jacobian") = true,
            "checkMesh's numbers for the current points, as a dict with the keys and values "
            "of checkMeshQuality -json (scaled_jacobian=False skips minScaledJacobian, which "
            "costs as much as the checks, and reports it as None).")
        .def(
            "sensitivity",
            [](PyCase& c, const py::handle& dJdx)
            {
                const Index n = c.session->mesh().n_points();
                const py::array flat = py::array::ensure(dJdx);
                const bool is_flat = flat && flat.ndim() == 1 && flat.size() == 3 * n;
                const Points g =
                    points_from(is_flat ? py::object(flat.attr("reshape")(-1, 3))
                                        : py::object(py::reinterpret_borrow<py::object>(dJdx)),
                                n, "dJ/dx");
                if (!g.allFinite())
                    throw InvalidInput("dJ/dx: a value is not finite (NaN or inf)");
                return points_array(
                    without_gil(*c.busy, [&] { return c.session->sensitivity(g); }));
            },
            py::arg("dJdx"),
            "The reverse pass of the last morph: for dJ/dx at every point ((nPoints, 3) or "
            "flat) the derivative dJ/dd with respect to each constrained point's prescribed "
            "displacement, as an (nPoints, 3) array (zero at the points the morph did not "
            "prescribe). The exact transpose of the morph's field with its choices held "
            "(greedy centres, jump constraints, the IDW tree), so that dJ = sum(dJ/dd * dd) to "
            "first order. For a morph in one step (points its repair moved are taken as "
            "following the field, with a warning), without wedges or cyclic patches (an "
            "InputError says which); a smoothed jump band is transposed with it (serial, "
            "without slip patches).")
        .def(
            "is_valid",
            [](PyCase& c) { return without_gil(*c.busy, [&] { return c.session->is_valid(); }); },
            "Whether the current points have no more negative-volume cells or wrongly "
            "oriented face pyramids than the mesh as read: the two checks a morph is judged "
            "by, nothing else (for line searches).")
        .def(
            "write",
            [](PyCase& c, bool overwrite)
            { return without_gil(*c.busy, [&] { return c.session->write(overwrite); }); },
            py::kw_only(), py::arg("overwrite") = false,
            "Write the current points atomically to the next time after the mesh's (or with "
            "overwrite=True into the mesh's own instance, keeping points.orig); returns the "
            "path. A refused morph is not written unless the case was opened with force.");
}

} // namespace meshmorph::python
