// SPDX-License-Identifier: GPL-3.0-or-later
#include "numpy_arrays.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

namespace meshmorph::python
{

namespace
{

using RealArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

//! The object as a numpy array of real numbers (not yet converted), refusing what is not
//! real numbers (strings, objects, complex, booleans) rather than letting numpy cast it.
py::array real_numbers(const py::handle& obj, const std::string& what)
{
    py::array any = py::array::ensure(obj);
    if (!any)
        throw py::type_error(what + ": expected an array of numbers");
    const char kind = any.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw py::type_error(what + ": expected real numbers, got an array of dtype " +
                             std::string(py::str(any.dtype())));
    return any;
}

//! C-contiguous float64 (a copy unless it is one already). The constructor raises the
//! Python error (e.g. MemoryError) where ensure() would return a null array.
RealArray as_doubles(const py::array& any)
{
    return RealArray(py::reinterpret_borrow<py::object>(any));
}

std::string shape_of(const py::array& a)
{
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d)
        s += (d ? ", " : "") + std::to_string(a.shape(d));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

} // namespace

Points points_from(const py::handle& obj, Index rows, const std::string& what)
{
    const py::array any = real_numbers(obj, what);
    // The shape is checked before the conversion: a wrong array is never copied.
    const bool shape_ok =
        any.ndim() == 2 && any.shape(1) == 3 && (rows < 0 || any.shape(0) == rows);
    if (!shape_ok)
        throw py::value_error(what + ": expected shape (" +
                              (rows < 0 ? std::string("n") : std::to_string(rows)) + ", 3), got " +
                              shape_of(any));
    const RealArray a = as_doubles(any);
    Points p(a.shape(0), 3);
    if (p.size() > 0)
        std::memcpy(p.data(), a.data(), sizeof(double) * std::size_t(p.size()));
    return p;
}

Vector3 vector_from(const py::handle& obj, const std::string& what)
{
    const py::array any = real_numbers(obj, what);
    if (any.ndim() != 1 || any.shape(0) != 3)
        throw py::value_error(what + ": expected a vector of 3 numbers, got shape " +
                              shape_of(any));
    const RealArray a = as_doubles(any);
    return Vector3(a.at(0), a.at(1), a.at(2));
}

std::vector<Index> labels_from(const py::handle& obj, const std::string& what)
{
    const py::array any = py::array::ensure(obj);
    if (!any)
        throw py::type_error(what + ": expected an array of point labels");
    const char kind = any.dtype().kind();
    if (any.size() > 0 && kind != 'i' && kind != 'u')
        throw py::type_error(what + ": point labels must be integers, got dtype " +
                             std::string(py::str(any.dtype())));
    if (any.ndim() != 1)
        throw py::value_error(what + ": expected a 1-D array of labels, got shape " +
                              shape_of(any));
    // Unsigned labels are read as unsigned, so that none wraps to a negative number.
    using Unsigned = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>;
    using Signed = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
    std::vector<Index> labels(std::size_t(any.size()));
    const auto narrow = [&](auto label, py::ssize_t k)
    {
        // Range-checked before narrowing to a 32-bit label build's Index.
        if (std::cmp_less(label, std::numeric_limits<Index>::min()) ||
            std::cmp_greater(label, std::numeric_limits<Index>::max()))
            throw py::value_error(what + ": label " + std::to_string(label) + " out of range");
        labels[std::size_t(k)] = static_cast<Index>(label);
    };
    if (kind == 'u')
    {
        const Unsigned a(py::reinterpret_borrow<py::object>(any));
        for (py::ssize_t k = 0; k < a.size(); ++k)
            narrow(a.data()[k], k);
    }
    else
    {
        const Signed a(py::reinterpret_borrow<py::object>(any));
        for (py::ssize_t k = 0; k < a.size(); ++k)
            narrow(a.data()[k], k);
    }
    return labels;
}

std::vector<double> reals_from(const py::handle& obj, const std::string& what)
{
    const py::array any = real_numbers(obj, what);
    if (any.ndim() != 1)
        throw py::value_error(what + ": expected a 1-D array, got shape " + shape_of(any));
    const RealArray a = as_doubles(any);
    return std::vector<double>(a.data(), a.data() + a.size());
}

py::array_t<double> points_view(const Points& points, const py::handle& owner)
{
    py::array_t<double> view({points.rows(), Eigen::Index(3)},
                             {py::ssize_t(3 * sizeof(double)), py::ssize_t(sizeof(double))},
                             points.data(), owner);
    py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return view;
}

py::array_t<double> points_array(Points&& points)
{
    auto* owned = new Points(std::move(points));
    const py::capsule free_when_done(owned, [](void* p) { delete static_cast<Points*>(p); });
    return py::array_t<double>({owned->rows(), Eigen::Index(3)},
                               {py::ssize_t(3 * sizeof(double)), py::ssize_t(sizeof(double))},
                               owned->data(), free_when_done);
}

py::array_t<std::int64_t> labels_array(const std::vector<Index>& labels)
{
    py::array_t<std::int64_t> a(py::ssize_t(labels.size()));
    std::copy(labels.begin(), labels.end(), a.mutable_data());
    return a;
}

} // namespace meshmorph::python
