// SPDX-License-Identifier: GPL-3.0-or-later
// Time directories and polyMesh instance lookup.
#include "meshmorph/io/case_instance.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <system_error>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_file.h"

namespace meshmorph::io
{
namespace fs = std::filesystem;

namespace
{

std::optional<double> parse_time_name(const std::string& name)
{
    if (name.empty())
        return std::nullopt;
    double value = 0;
    const char* begin = name.data();
    const char* end = name.data() + name.size();
    if (*begin == '+')
        ++begin;
    const std::from_chars_result r = std::from_chars(begin, end, value);
    if (r.ec != std::errc() || r.ptr != end || !std::isfinite(value))
        return std::nullopt;
    return value;
}

// Relative comparison tolerance for time values (names are printed with few digits).
constexpr double time_tolerance = 1e-9;

bool time_equal(double a, double b)
{
    return std::abs(a - b) <= time_tolerance * std::max({std::abs(a), std::abs(b), 1e-300});
}

bool time_less_equal(double a, double b)
{
    return a < b || time_equal(a, b);
}

std::string known_times(const std::vector<TimeDir>& times)
{
    std::string s;
    for (const TimeDir& t : times)
        s += (s.empty() ? "" : " ") + t.name;
    return s.empty() ? std::string("none") : s;
}

} // namespace

std::vector<TimeDir> list_times(const fs::path& case_dir)
{
    std::vector<TimeDir> times;
    std::error_code ec;
    fs::directory_iterator it(case_dir, ec);
    if (ec)
        return times;
    for (const fs::directory_entry& entry : it)
    {
        std::error_code type_ec;
        if (!entry.is_directory(type_ec))
            continue;
        const std::string name = entry.path().filename().string();
        if (const std::optional<double> value = parse_time_name(name))
            times.push_back({name, *value});
    }
    std::sort(times.begin(), times.end(),
              [](const TimeDir& a, const TimeDir& b)
              { return a.value < b.value || (a.value == b.value && a.name < b.name); });
    return times;
}

std::string select_time(const std::vector<TimeDir>& times, const TimeSelection& selection)
{
    switch (selection.mode)
    {
    case TimeSelection::Mode::first:
    case TimeSelection::Mode::start:
        return times.empty() ? std::string("constant") : times.front().name;
    case TimeSelection::Mode::latest:
        return times.empty() ? std::string("constant") : times.back().name;
    case TimeSelection::Mode::time:
        break;
    }
    if (selection.time == "constant")
        return "constant";
    for (const TimeDir& t : times)
        if (t.name == selection.time)
            return t.name;
    const std::optional<double> value = parse_time_name(selection.time);
    if (!value)
        throw InvalidInput("-time " + selection.time + ": not a number or 'constant'");
    for (const TimeDir& t : times)
        if (time_equal(t.value, *value))
            return t.name;
    throw InvalidInput("-time " + selection.time +
                       ": no such time directory (times: " + known_times(times) + ")");
}

fs::path poly_mesh_dir(const fs::path& case_dir, const std::string& instance,
                       const std::string& region)
{
    fs::path dir = case_dir / instance;
    if (!region.empty() && region != "region0")
        dir /= region;
    return dir / "polyMesh";
}

bool is_motion_result(const fs::path& case_dir, const std::string& time, const std::string& region)
{
    const fs::path dir = poly_mesh_dir(case_dir, time, region);
    return foam_file_exists(dir / "points") && !foam_file_exists(dir / "faces");
}

std::vector<TimeDir> start_times(const fs::path& case_dir, const std::vector<TimeDir>& times,
                                 const std::string& region)
{
    std::vector<TimeDir> out;
    for (const TimeDir& t : times)
        if (!is_motion_result(case_dir, t.name, region))
            out.push_back(t);
    return out;
}

std::string find_instance(const fs::path& case_dir, const std::vector<TimeDir>& times,
                          const std::string& time, const std::string& key,
                          const std::string& region)
{
    if (time != "constant")
    {
        std::optional<double> t_value;
        for (const TimeDir& t : times)
            if (t.name == time)
                t_value = t.value;
        if (!t_value)
            t_value = parse_time_name(time);
        if (!t_value)
            throw InvalidInput("time '" + time + "' is not a number or 'constant'");
        for (auto it = times.rbegin(); it != times.rend(); ++it)
            if (time_less_equal(it->value, *t_value) &&
                foam_file_exists(poly_mesh_dir(case_dir, it->name, region) / key))
                return it->name;
    }
    const fs::path constant = poly_mesh_dir(case_dir, "constant", region);
    if (!foam_file_exists(constant / key))
        throw IoError(
            "Cannot find polyMesh file '" + key + "' in " + constant.string() +
            (time == "constant" ? std::string() : " nor in a time directory up to " + time));
    return "constant";
}

std::string format_time_name(double value, TimeFormat format, int precision)
{
    std::ostringstream os;
    os.imbue(std::locale::classic());
    if (format == TimeFormat::fixed)
        os.setf(std::ios::fixed, std::ios::floatfield);
    else if (format == TimeFormat::scientific)
        os.setf(std::ios::scientific, std::ios::floatfield);
    os.precision(precision);
    // Avoid "-0".
    os << (value == 0 ? 0.0 : value);
    return os.str();
}

TimeSettings read_time_settings(const fs::path& case_dir)
{
    TimeSettings settings;
    const fs::path path = case_dir / "system" / "controlDict";
    if (!foam_file_exists(path))
        return settings;
    // Only the time settings are read: function objects (#includeFunc) and computed
    // entries elsewhere in the stock tutorials' controlDicts do not matter.
    ParseOptions lenient;
    lenient.skip_unsupported = true;
    const FoamDictionary dict = read_dictionary(path, lenient);
    settings.delta_t = dict.get_or<double>("deltaT", 1.0);
    if (!(settings.delta_t > 0))
        throw dict.entry("deltaT").error(
            "deltaT must be positive: the mesh is written to the next time, the current one "
            "plus deltaT (mesh-generation cases often set 0; -overwrite writes in place)");
    const std::string format = dict.get_or<std::string>("timeFormat", "general");
    if (format == "general")
        settings.format = TimeFormat::general;
    else if (format == "fixed")
        settings.format = TimeFormat::fixed;
    else if (format == "scientific")
        settings.format = TimeFormat::scientific;
    else
        throw dict.entry("timeFormat")
            .error("unknown timeFormat '" + format + "' (expected general, fixed, scientific)");
    settings.precision = dict.get_or<std::int32_t>("timePrecision", 6);
    if (settings.precision < 1 || settings.precision > 17)
        throw dict.entry("timePrecision").error("timePrecision must be in 1..17");
    return settings;
}

std::string next_time_name(const std::vector<TimeDir>& times, const std::string& time,
                           const TimeSettings& settings)
{
    double current = 0;
    if (time == "constant")
        current = times.empty() ? 0.0 : times.front().value;
    else if (const std::optional<double> v = parse_time_name(time))
        current = *v;
    else
        throw InvalidInput("time '" + time + "' is not a number or 'constant'");
    const double next = current + settings.delta_t;
    const std::string current_name =
        time == "constant" ? format_time_name(current, settings.format, settings.precision) : time;
    // OpenFOAM raises the precision when the new name would repeat the old one.
    for (int precision = settings.precision; precision <= 17; ++precision)
    {
        const std::string name = format_time_name(next, settings.format, precision);
        if (time == "constant" && times.empty())
            return name;
        if (name != current_name)
            return name;
    }
    return format_time_name(next, settings.format, 17);
}

std::filesystem::path default_vtk_file(const std::filesystem::path& case_dir,
                                       const std::string& app_name, const std::string& region,
                                       const std::string& time)
{
    return case_dir / "VTK" /
           (app_name + "_" + (region.empty() ? "" : region + "_") + time + ".vtu");
}

} // namespace meshmorph::io
