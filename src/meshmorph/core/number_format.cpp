// SPDX-License-Identifier: GPL-3.0-or-later
// std::to_chars with chars_format::general and a precision is specified as printf's %.*g in
// the C locale, and is faster than snprintf (no locale, no format parsing).
#include "meshmorph/core/number_format.h"

#include <charconv>

namespace meshmorph
{

void append_scalar(std::string& out, double value, int precision)
{
    char buffer[40];
    const std::to_chars_result r =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, precision);
    out.append(buffer, r.ptr);
}

std::string format_scalar(double value, int precision)
{
    std::string out;
    append_scalar(out, value, precision);
    return out;
}

} // namespace meshmorph
