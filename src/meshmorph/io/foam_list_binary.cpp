// SPDX-License-Identifier: GPL-3.0-or-later
// Decoding binary list blocks (io/foam_list_binary.h).
#include "meshmorph/io/foam_list_binary.h"

#include <bit>
#include <cstring>
#include <limits>

namespace meshmorph::io::list_detail
{

static_assert(std::endian::native == std::endian::little,
              "binary OpenFOAM files are little-endian; big-endian hosts are not supported");

namespace
{

template <class Int, class L>
void decode_labels_as(std::string_view raw, L* out, std::size_t n, const FoamTokenizer& tok,
                      const ListStart& start, std::size_t data_offset, const std::string& what)
{
    if constexpr (sizeof(Int) == sizeof(L))
    {
        std::memcpy(out, raw.data(), n * sizeof(L));
    }
    else
    {
        for (std::size_t i = 0; i < n; ++i)
        {
            Int v;
            std::memcpy(&v, raw.data() + i * sizeof(Int), sizeof(Int));
            if constexpr (sizeof(Int) > sizeof(L))
            {
                if (v < std::numeric_limits<L>::min() || v > std::numeric_limits<L>::max())
                    throw binary_error(tok, start.line, data_offset + i * sizeof(Int), what,
                                       "label " + std::to_string(v) + " does not fit in a " +
                                           std::to_string(8 * sizeof(L)) + "-bit label");
            }
            out[i] = static_cast<L>(v);
        }
    }
}

template <class L>
void decode_labels_into(std::string_view raw, int label_bytes, L* out, std::size_t n,
                        const FoamTokenizer& tok, const ListStart& start, std::size_t data_offset,
                        const std::string& what)
{
    if (label_bytes == 4)
        decode_labels_as<std::int32_t>(raw, out, n, tok, start, data_offset, what);
    else
        decode_labels_as<std::int64_t>(raw, out, n, tok, start, data_offset, what);
}

} // namespace

void decode_labels(std::string_view raw, int label_bytes, std::int32_t* out, std::size_t n,
                   const FoamTokenizer& tok, const ListStart& start, std::size_t data_offset,
                   const std::string& what)
{
    decode_labels_into(raw, label_bytes, out, n, tok, start, data_offset, what);
}

void decode_labels(std::string_view raw, int label_bytes, std::int64_t* out, std::size_t n,
                   const FoamTokenizer& tok, const ListStart& start, std::size_t data_offset,
                   const std::string& what)
{
    decode_labels_into(raw, label_bytes, out, n, tok, start, data_offset, what);
}

void decode_scalars(std::string_view raw, int scalar_bytes, double* out, std::size_t n)
{
    if (scalar_bytes == 8)
        std::memcpy(out, raw.data(), n * sizeof(double));
    else
        for (std::size_t i = 0; i < n; ++i)
        {
            float v;
            std::memcpy(&v, raw.data() + i * sizeof(float), sizeof(float));
            out[i] = static_cast<double>(v);
        }
}

} // namespace meshmorph::io::list_detail
