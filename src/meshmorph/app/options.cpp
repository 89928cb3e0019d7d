// SPDX-License-Identifier: GPL-3.0-or-later
// OpenFOAM-style option parsing and the generated -help text.
#include "meshmorph/app/options.h"

#include <algorithm>
#include <charconv>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "meshmorph/core/log.h"

namespace meshmorph::app
{

namespace
{

//! An argument that is a value, not an option: not starting with '-', or a negative number.
bool is_value(const std::string& arg)
{
    return arg.size() < 2 || arg[0] != '-' || (arg[1] >= '0' && arg[1] <= '9') || arg[1] == '.';
}

} // namespace

Options::Options(std::string app_name, std::string description, std::vector<OptionSpec> specs,
                 std::vector<ExitCode> exit_codes)
    : app_name_(std::move(app_name)), description_(std::move(description)),
      specs_(std::move(specs)), exit_codes_(std::move(exit_codes))
{
    if (!find_spec("help"))
        specs_.push_back({"help", "", "Print this usage information and exit"});
    for (std::size_t i = 0; i < specs_.size(); ++i)
        for (std::size_t j = i + 1; j < specs_.size(); ++j)
            if (specs_[i].name == specs_[j].name)
                throw std::logic_error("option -" + specs_[i].name + " declared twice");
}

const OptionSpec* Options::find_spec(const std::string& name) const
{
    for (const OptionSpec& spec : specs_)
        if (spec.name == name)
            return &spec;
    return nullptr;
}

void Options::parse(int argc, const char* const argv[])
{
    values_.clear();
    positional_.clear();
    help_requested_ = false;
    command_line_.clear();
    for (int i = 0; i < argc; ++i)
    {
        if (i > 0)
            command_line_ += ' ';
        command_line_ += argv[i];
    }
    // A help request wins over every other error, as in OpenFOAM.
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "-help" || arg == "--help" || arg == "-h" || arg == "-help-full")
        {
            help_requested_ = true;
            return;
        }
    }
    const OptionSpec* previous_flag = nullptr; // the flag just before, for stray arguments
    // The list option just before (`-variant 0 1 0`: the shell split an unquoted list).
    const OptionSpec* previous_list = nullptr;
    std::string list_words;
    for (int i = 1; i < argc; ++i)
    {
        std::string arg = argv[i];
        if (is_value(arg))
        {
            if (previous_list && positional_.size() >= positional_names_.size())
            {
                list_words += " " + arg;
                if (i + 1 < argc && is_value(argv[i + 1]))
                    continue; // gather the rest of the split list for the hint
                throw UsageError("unexpected argument '" + arg + "' after -" + previous_list->name +
                                 ": a list goes in one quoted argument, " + "e.g. -" +
                                 previous_list->name + " \"(" + list_words + ")\"");
            }
            if (previous_flag && positional_.size() >= positional_names_.size())
                throw UsageError("unexpected argument '" + arg + "' after -" + previous_flag->name +
                                 ", which takes no argument" +
                                 (previous_flag->stray_argument_hint.empty()
                                      ? std::string(" (see " + app_name_ + " -help)")
                                      : ": " + previous_flag->stray_argument_hint + " " + arg));
            positional_.push_back(arg);
            previous_flag = nullptr;
            previous_list = nullptr;
            continue;
        }
        previous_flag = nullptr;
        previous_list = nullptr;
        std::string name = arg.substr(arg[1] == '-' ? 2 : 1);
        std::optional<std::string> inline_value;
        if (const std::size_t eq = name.find('='); eq != std::string::npos && arg[1] == '-')
        {
            inline_value = name.substr(eq + 1);
            name = name.substr(0, eq);
        }
        const OptionSpec* spec = find_spec(name);
        if (!spec)
            throw UsageError("unknown option '" + arg + "' (see " + app_name_ + " -help)");
        if (values_.count(name))
            throw UsageError("option -" + name + " given more than once");
        if (spec->argument.empty())
        {
            if (inline_value)
                throw UsageError("option -" + name + " takes no argument");
            values_[name] = "";
            previous_flag = spec;
            continue;
        }
        if (inline_value)
        {
            values_[name] = *inline_value;
            continue;
        }
        if (i + 1 >= argc)
            throw UsageError("option -" + name + " expects an argument " + spec->argument);
        values_[name] = argv[++i];
        if (spec->argument.rfind("(", 0) == 0)
        {
            previous_list = spec;
            list_words = values_[name];
        }
    }
    if (positional_.size() != positional_names_.size())
    {
        if (positional_names_.empty())
            throw UsageError("unexpected argument '" + positional_.front() + "' (see " + app_name_ +
                             " -help)");
        throw UsageError("expected " + std::to_string(positional_names_.size()) +
                         " argument(s), got " + std::to_string(positional_.size()));
    }
}

bool Options::found(const std::string& name) const
{
    if (name == "help")
        return help_requested_;
    if (!find_spec(name))
        throw std::logic_error("option -" + name + " is not in the option table");
    return values_.count(name) > 0;
}

std::optional<std::string> Options::get(const std::string& name) const
{
    if (!find_spec(name))
        throw std::logic_error("option -" + name + " is not in the option table");
    const auto it = values_.find(name);
    if (it == values_.end())
        return std::nullopt;
    return it->second;
}

std::string Options::value_or(const std::string& name, const std::string& fallback) const
{
    return get(name).value_or(fallback);
}

std::optional<double> Options::get_scalar(const std::string& name) const
{
    const std::optional<std::string> text = get(name);
    if (!text)
        return std::nullopt;
    double value = 0;
    const char* begin = text->data();
    const char* end = begin + text->size();
    const std::from_chars_result r = std::from_chars(begin, end, value);
    if (text->empty() || r.ec != std::errc() || r.ptr != end)
        throw UsageError("option -" + name + ": '" + *text + "' is not a number");
    return value;
}

std::string Options::help_text() const
{
    std::ostringstream out;
    out << "\nUsage: " << app_name_ << " [OPTIONS]";
    for (const std::string& p : positional_names_)
        out << " <" << p << ">";
    out << "\n";
    std::size_t width = 0;
    for (const OptionSpec& spec : specs_)
        width = std::max(width, spec.name.size() + 2 +
                                    (spec.argument.empty() ? 0 : spec.argument.size() + 3));
    out << "options:\n";
    std::vector<OptionSpec> sorted = specs_;
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const OptionSpec& a, const OptionSpec& b) { return a.name < b.name; });
    for (const OptionSpec& spec : sorted)
    {
        std::string left = "  -" + spec.name;
        if (!spec.argument.empty())
            left += " <" + spec.argument + ">";
        out << left << std::string(width + 4 - std::min(width + 3, left.size()), ' ') << spec.help
            << "\n";
    }
    if (!description_.empty())
        out << "\n" << description_ << "\n";
    if (!exit_codes_.empty())
    {
        out << "\nExit status:\n";
        for (const ExitCode& code : exit_codes_)
            out << "  " << code.code << "  " << code.meaning << "\n";
    }
    out << "\n";
    return out.str();
}

std::optional<int> parse_command_line(Options& options, int argc, const char* const argv[],
                                      std::ostream& out)
{
    try
    {
        options.parse(argc, argv);
    }
    catch (const UsageError& e)
    {
        log::error() << e.what() << "\nUsage: " << options.app_name() << " [OPTIONS]; see "
                     << options.app_name() << " -help";
        return exit_input_error;
    }
    if (options.help_requested())
    {
        out << options.help_text();
        return 0;
    }
    return std::nullopt;
}

std::vector<OptionSpec> vtk_option_specs(const std::string& app_name, const std::string& contents)
{
    const std::string file = "VTK/" + app_name + "_[<region>_]<time>.vtu";
    return {{"vtk", "", "Also write " + file + " in the case with " + contents,
             "-vtk writes " + file + " in the case; to choose the file, use -vtkFile"},
            {"vtkFile", "FILE", "Like -vtk, but write FILE (relative to the working directory)"}};
}

bool vtk_requested(const Options& options)
{
    return options.found("vtk") || options.found("vtkFile");
}

std::filesystem::path vtk_file_argument(const Options& options)
{
    const std::optional<std::string> file = options.get("vtkFile");
    if (!file)
        return {};
    if (file->empty())
        throw UsageError("-vtkFile: expected a file name");
    return std::filesystem::absolute(*file);
}

std::string region_option(const Options& options)
{
    const std::optional<std::string> region = options.get("region");
    if (!region || *region == "region0")
        return "";
    if (region->empty() || *region == "." || *region == ".." ||
        region->find('/') != std::string::npos)
        throw UsageError("-region '" + *region +
                         "': expected the name of a region (a directory of constant/, e.g. "
                         "-region fluid)");
    return *region;
}

} // namespace meshmorph::app
