// SPDX-License-Identifier: GPL-3.0-or-later
// locate_list_element (io/foam_lists.h): where the i-th element of a list starts, without
// reading the list: the mesh reader names the line of a bad label this way.
#include "meshmorph/io/foam_lists.h"

#include <vector>

#include "meshmorph/io/foam_face_lists.h"
#include "meshmorph/io/foam_list_start.h"

namespace meshmorph::io
{

using namespace list_detail;

ElementLocation locate_list_element(FoamTokenizer& tok, const FoamHeader& header, ListKind kind,
                                    std::size_t index)
{
    try
    {
        ListReadOptions options;
        options.what = "list";
        options.parallel = false;
        if (kind == ListKind::face_compact_value)
        {
            read_label_list(tok, header, options); // offsets
            kind = ListKind::label;
        }
        std::size_t element_bytes = 0;
        if (header.is_binary())
            element_bytes = kind == ListKind::label    ? header.label_bytes
                            : kind == ListKind::scalar ? header.scalar_bytes
                            : kind == ListKind::vector ? 3 * header.scalar_bytes
                                                       : 0;
        const ListStart start = read_list_start(tok, header, options,
                                                kind == ListKind::vector ? min_chars_vector
                                                : kind == ListKind::face ? min_chars_face
                                                                         : min_chars_label,
                                                element_bytes);
        if (start.open != '(' || (start.has_size && index >= start.size))
            return {};
        if (element_bytes > 0)
            return {start.line, tok.offset() + index * element_bytes};
        std::vector<Index> scratch;
        for (std::size_t i = 0; i < index; ++i)
        {
            std::int64_t l;
            double d;
            double v[3];
            switch (kind)
            {
            case ListKind::label:
                if (!tok.read_label(l))
                    return {};
                break;
            case ListKind::scalar:
                if (!tok.read_scalar(d))
                    return {};
                break;
            case ListKind::vector:
                tok.read_vector(v);
                break;
            case ListKind::face:
            case ListKind::face_compact_value:
                scratch.clear();
                if (header.is_binary())
                    read_binary_face(tok, header, scratch, i, options.what);
                else
                    read_ascii_face(tok, scratch, start, i, options.what);
                break;
            }
        }
        tok.skip_whitespace_and_comments();
        return {tok.line(), tok.offset()};
    }
    catch (const Error&)
    {
        return {};
    }
}

} // namespace meshmorph::io
