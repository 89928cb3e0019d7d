// SPDX-License-Identifier: GPL-3.0-or-later
// The list writers of io/foam_lists.h (append_*): OpenFOAM's ASCII layout of lists
// (List::writeList: short lists on one line, uniform lists as `N{v}`) and binary blocks, so
// that every file meshmorph writes lays out its lists as OpenFOAM does.
#include "meshmorph/core/number_format.h"
#include "meshmorph/io/foam_lists.h"

#include <array>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>

namespace meshmorph::io
{

static_assert(std::endian::native == std::endian::little,
              "binary OpenFOAM files are little-endian; big-endian hosts are not supported");

namespace
{

void append_label_text(std::string& out, std::int64_t v)
{
    char buf[24];
    const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

template <class Int> void append_raw_labels(std::string& out, const std::vector<Index>& values)
{
    if constexpr (sizeof(Int) == sizeof(Index))
    {
        out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(Index));
    }
    else
    {
        const std::size_t base = out.size();
        out.resize(base + values.size() * sizeof(Int));
        for (std::size_t i = 0; i < values.size(); ++i)
        {
            const Int v = static_cast<Int>(values[i]);
            std::memcpy(out.data() + base + i * sizeof(Int), &v, sizeof(Int));
        }
    }
}

void append_binary_labels(std::string& out, const std::vector<Index>& values, int label_bytes)
{
    // OpenFOAM: nl << size << nl, then `(` raw `)` unless empty.
    out += '\n';
    append_label_text(out, static_cast<std::int64_t>(values.size()));
    out += '\n';
    if (values.empty())
        return;
    out += '(';
    if (label_bytes == 8)
        append_raw_labels<std::int64_t>(out, values);
    else
        append_raw_labels<std::int32_t>(out, values);
    out += ')';
}

// OpenFOAM's ASCII List layout for contiguous elements (List::writeList, shortListLen 10).
template <class Elem, class AppendOne>
void append_ascii_list(std::string& out, std::size_t n, Elem elem, AppendOne append_one,
                       bool allow_uniform)
{
    bool uniform = allow_uniform && n > 1;
    for (std::size_t i = 1; uniform && i < n; ++i)
        uniform = elem(i) == elem(0);
    if (uniform)
    {
        append_label_text(out, static_cast<std::int64_t>(n));
        out += '{';
        append_one(out, 0);
        out += '}';
        return;
    }
    if (n <= 10)
    {
        append_label_text(out, static_cast<std::int64_t>(n));
        out += '(';
        for (std::size_t i = 0; i < n; ++i)
        {
            if (i > 0)
                out += ' ';
            append_one(out, i);
        }
        out += ')';
        return;
    }
    out += '\n';
    append_label_text(out, static_cast<std::int64_t>(n));
    out += "\n(\n";
    for (std::size_t i = 0; i < n; ++i)
    {
        append_one(out, i);
        out += '\n';
    }
    out += ")\n";
}

} // namespace

void append_label_list(std::string& out, const std::vector<Index>& values, FoamFormat format,
                       int label_bytes, bool allow_uniform)
{
    if (format == FoamFormat::binary)
    {
        append_binary_labels(out, values, label_bytes);
        return;
    }
    append_ascii_list(
        out, values.size(), [&](std::size_t i) { return values[i]; },
        [&](std::string& o, std::size_t i) { append_label_text(o, values[i]); }, allow_uniform);
}

void append_vector_list(std::string& out, const Points& values, FoamFormat format, int digits)
{
    const std::size_t n = static_cast<std::size_t>(values.rows());
    if (format == FoamFormat::binary)
    {
        out += '\n';
        append_label_text(out, static_cast<std::int64_t>(n));
        out += '\n';
        if (n == 0)
            return;
        out += '(';
        out.append(reinterpret_cast<const char*>(values.data()), n * 3 * sizeof(double));
        out += ')';
        return;
    }
    out.reserve(out.size() + n * (3 * (digits + 7) + 3) + 32);
    append_ascii_list(
        out, n,
        [&](std::size_t i)
        {
            return std::array<double, 3>{values(static_cast<Eigen::Index>(i), 0),
                                         values(static_cast<Eigen::Index>(i), 1),
                                         values(static_cast<Eigen::Index>(i), 2)};
        },
        [&](std::string& o, std::size_t i)
        {
            const Eigen::Index r = static_cast<Eigen::Index>(i);
            o += '(';
            append_scalar(o, values(r, 0), digits);
            o += ' ';
            append_scalar(o, values(r, 1), digits);
            o += ' ';
            append_scalar(o, values(r, 2), digits);
            o += ')';
        },
        true);
}

void append_face_list(std::string& out, const CompactList& faces, FoamFormat format,
                      int label_bytes)
{
    if (format == FoamFormat::binary)
    {
        append_binary_labels(out, faces.offsets, label_bytes);
        append_binary_labels(out, faces.values, label_bytes);
        return;
    }
    // faceList is not contiguous: multi-line unless it has at most one face.
    const Index n = faces.size();
    const auto append_face = [&](std::string& o, Index f)
    {
        const std::span<const Index> face = faces[f];
        append_ascii_list(
            o, face.size(), [&](std::size_t i) { return face[i]; },
            [&](std::string& s, std::size_t i) { append_label_text(s, face[i]); }, true);
    };
    if (n <= 1)
    {
        append_label_text(out, n);
        out += '(';
        if (n == 1)
            append_face(out, 0);
        out += ')';
        return;
    }
    out.reserve(out.size() + faces.values.size() * 8 + static_cast<std::size_t>(n) * 4);
    out += '\n';
    append_label_text(out, n);
    out += "\n(\n";
    for (Index f = 0; f < n; ++f)
    {
        append_face(out, f);
        out += '\n';
    }
    out += ")\n";
}

} // namespace meshmorph::io
