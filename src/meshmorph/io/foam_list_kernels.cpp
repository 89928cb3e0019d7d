// SPDX-License-Identifier: GPL-3.0-or-later
// The once-per-list parts of the fast ASCII list path (io/foam_list_kernels.h): finding the
// end of a list body, splitting it into chunks, and deciding whether threads pay off.
#include "meshmorph/io/foam_list_kernels.h"

#include <cstdlib>
#include <cstring>

#include <omp.h>

namespace meshmorph::io::list_detail
{

namespace
{

// Lists at least this long (in bytes of text) are parsed in parallel.
constexpr std::size_t parallel_min_bytes = std::size_t(1) << 20;

// Find the end of a list body: the position of its matching ')' for a flat list of
// numbers or of `(…)` elements nested one level, scanning raw characters. Returns npos if
// not found. Only called when the body holds no comments.
std::size_t find_list_end(std::string_view buf, std::size_t from, int element_depth)
{
    int depth = 0;
    const char* p = buf.data() + from;
    const char* const end = buf.data() + buf.size();
    for (; p < end; ++p)
    {
        const char c = *p;
        if (c == '(')
        {
            if (++depth > element_depth)
                return std::string_view::npos;
        }
        else if (c == ')')
        {
            if (depth == 0)
                return static_cast<std::size_t>(p - buf.data());
            --depth;
        }
    }
    return std::string_view::npos;
}

} // namespace

std::vector<Chunk> split_lines(std::string_view buf, std::size_t begin, std::size_t end, int parts)
{
    std::vector<Chunk> chunks;
    const std::size_t len = end - begin;
    std::size_t pos = begin;
    for (int k = 0; k < parts && pos < end; ++k)
    {
        std::size_t stop = k + 1 == parts ? end : begin + len * (k + 1) / parts;
        if (stop < pos)
            stop = pos;
        if (stop < end)
        {
            const void* nl = std::memchr(buf.data() + stop, '\n', end - stop);
            stop =
                nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - buf.data()) + 1 : end;
        }
        chunks.push_back({pos, stop, 0, 0});
        pos = stop;
    }
    return chunks;
}

int chunk_count()
{
    return std::max(1, omp_get_max_threads()) * 4;
}

// Usually the list is the last thing in its file, so the last ')' of the file (followed
// only by comments) closes it; otherwise the brackets are counted.
std::size_t list_body_end(const FoamTokenizer& tok, int element_depth)
{
    const std::string_view buf = tok.buffer();
    const std::size_t begin = tok.offset();
    const std::size_t last = buf.rfind(')');
    if (last != std::string_view::npos && last >= begin)
    {
        FoamTokenizer tail(buf.substr(last + 1), tok.path());
        try
        {
            if (tail.at_end())
                return last;
        }
        catch (const ParseError&)
        {
        }
    }
    return find_list_end(buf, begin, element_depth);
}

// Threads only pay off on idle cores: on a machine already busy (1-minute load average
// above cores - 1) the OpenMP team's waiting threads cost more than they gain (measured on
// a loaded 2-core machine: 2 threads 100 MB/s, 1 thread 185 MB/s on motorBike).
bool worth_parallel(const FoamTokenizer& tok, const ListReadOptions& options)
{
    if (options.force_parallel)
        return true;
    if (!options.parallel || tok.buffer().size() - tok.offset() < parallel_min_bytes ||
        omp_get_max_threads() < 2)
        return false;
    double load = 0;
    if (::getloadavg(&load, 1) == 1 && load > omp_get_num_procs() - 1)
        return false;
    return true;
}

} // namespace meshmorph::io::list_detail
