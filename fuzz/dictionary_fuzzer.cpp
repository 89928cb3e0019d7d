// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the dictionary parser (io/foam_dictionary*), then every typed getter on
// every entry. Includes resolve in memory to one small fixed file, so no input reaches the
// disk. Input errors must be meshmorph::Error; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_scratch.h"
#include "meshmorph/io/foam_dictionary.h"

namespace
{

using namespace meshmorph;
using namespace meshmorph::io;

const char* const included_text = "a 1;\nb { c (1 2 3); d $a; }\n\"r.*\" word;\nl 2(4 5);\n";

std::optional<std::string> read_included(const std::filesystem::path& path)
{
    if (path.filename().string().find("missing") != std::string::npos)
        return std::nullopt;
    return std::string(included_text);
}

template <class T> void try_get(const FoamEntry& entry, std::size_t first = 0)
{
    try
    {
        (void)entry.get<T>(first);
    }
    catch (const Error&)
    {
    }
}

void visit(const FoamDictionary& dict)
{
    for (const FoamEntry& entry : dict.entries())
    {
        (void)dict.find(entry.keyword()); // exact and regex lookup
        if (entry.is_dict())
        {
            visit(entry.dict());
            continue;
        }
        try_get<double>(entry);
        try_get<std::int32_t>(entry);
        try_get<std::int64_t>(entry);
        try_get<bool>(entry);
        try_get<std::string>(entry);
        try_get<Vector3>(entry);
        try_get<Vector3>(entry, 1); // `uniform (x y z)`
        try_get<std::vector<double>>(entry);
        try_get<std::vector<std::int32_t>>(entry);
        try_get<std::vector<std::string>>(entry);
        try_get<std::vector<Vector3>>(entry, 1); // `nonuniform List<vector> N(...)`
    }
    (void)dict.referenced_variables();
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    fuzz::silence_log();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    ParseOptions options;
    options.read_file = read_included;
    options.case_dir = "/fuzz/case";
    // Odd sizes are read as a controlDict is (unsupported directives skipped), even sizes as
    // morphDict (every unsupported directive an error): both modes from one target.
    options.skip_unsupported = size % 2 == 1;
    try
    {
        visit(parse_dictionary(fuzz::as_text(data, size), "/fuzz/case/system/dict", options));
    }
    catch (const Error&)
    {
    }
    return 0;
}
