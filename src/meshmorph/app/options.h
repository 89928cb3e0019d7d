// SPDX-License-Identifier: GPL-3.0-or-later
//! \file One OpenFOAM-style option table per application: parsing, `-help` text, values.
//!
//! Options use a single dash (`-case DIR`, `-latestTime`); `--name` is accepted too.
//! Unknown options and missing arguments raise UsageError (applications return exit
//! code 2 for it). The table generates the `-help` text, so help and parser cannot drift.
//!
//! Conventions shared by the applications: options that write a file take it as argument
//! (`-json FILE`), except VTK output, which follows foamToVTK: `-vtk` writes
//! `<case>/VTK/<app>_[<region>_]<time>.vtu`, `-vtkFile FILE` writes FILE instead.
#pragma once

#include "meshmorph/app/exit_status.h"
#include "meshmorph/app/usage_error.h"
#include <filesystem>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/core/exceptions.h"

namespace meshmorph::app
{

//! One row of the option table.
struct OptionSpec
{
    std::string name;     //!< without the dash, e.g. "case"
    std::string argument; //!< argument name shown in -help ("DIR"); empty for a flag
    std::string help;     //!< one-line description
    //! For a flag: said when an argument follows it (`-vtk out.vtu`); the argument is
    //! appended, e.g. "to choose the file, use -vtkFile" + " out.vtu".
    std::string stray_argument_hint = {};
};

//! One documented exit status of an application.
struct ExitCode
{
    int code;
    std::string meaning;
};

//! The option table of one application and, after parse(), its values.
class Options
{
public:
    //! \param app_name executable name (lowerCamelCase). \param description one paragraph
    //! for -help. \param specs the options (`-help` is always added).
    //! \param exit_codes documented exit statuses, listed by -help.
    Options(std::string app_name, std::string description, std::vector<OptionSpec> specs,
            std::vector<ExitCode> exit_codes = {});

    //! Parse argv[1..argc). Positional arguments are rejected unless `n_positional` > 0
    //! (their names shown in the Usage line).
    //! \throw UsageError on an unknown option, a missing argument, a repeated option or a
    //! wrong number of positional arguments.
    void parse(int argc, const char* const argv[]);

    //! Whether `-name` was given (for a flag or an option with argument).
    bool found(const std::string& name) const;
    //! The argument of `-name`, if given. \throw std::logic_error if `name` is not in the table.
    std::optional<std::string> get(const std::string& name) const;
    //! The argument of `-name`, or `fallback`.
    std::string value_or(const std::string& name, const std::string& fallback) const;
    //! The argument of `-name` as a double. \throw UsageError if it is not a number.
    std::optional<double> get_scalar(const std::string& name) const;
    //! Whether -help / --help / -h was given (parse() then skips other validation).
    bool help_requested() const { return help_requested_; }

    //! Declare positional arguments (names for the Usage line), e.g. {"FILE"}.
    void set_positional(std::vector<std::string> names) { positional_names_ = std::move(names); }
    const std::vector<std::string>& positional() const { return positional_; }

    //! The generated -help text (Usage line, description, options, exit codes).
    std::string help_text() const;
    //! The command line as typed (argv joined with spaces), for the banner.
    const std::string& command_line() const { return command_line_; }
    const std::string& app_name() const { return app_name_; }
    const std::vector<OptionSpec>& specs() const { return specs_; }

private:
    const OptionSpec* find_spec(const std::string& name) const;

    std::string app_name_;
    std::string description_;
    std::vector<OptionSpec> specs_;
    std::vector<ExitCode> exit_codes_;
    std::vector<std::string> positional_names_;
    std::vector<std::string> positional_;
    std::map<std::string, std::string> values_;
    bool help_requested_ = false;
    std::string command_line_;
};

//! Parse the command line the way every meshmorph application does: on -help print the
//! help text to `out` and return 0; on a UsageError log the error "<what>" and a usage hint
//! (log::error) and return exit_input_error; otherwise return std::nullopt (continue).
std::optional<int> parse_command_line(Options& options, int argc, const char* const argv[],
                                      std::ostream& out);

//! \brief The `-vtk` and `-vtkFile FILE` rows of an application's option table, worded the
//! same in every application. \param contents what the file holds, e.g. "per-cell quality
//! fields".
std::vector<OptionSpec> vtk_option_specs(const std::string& app_name, const std::string& contents);

//! Whether `-vtk` or `-vtkFile` was given.
bool vtk_requested(const Options& options);

//! \brief The FILE of `-vtkFile FILE` as an absolute path (relative paths are from the working
//! directory); empty when not given (then `-vtk` writes default_vtk_file()).
//! \throw UsageError on an empty FILE.
std::filesystem::path vtk_file_argument(const Options& options);

//! \brief The `-region NAME` of a command line: "" when absent or `region0` (OpenFOAM's
//! default region, whose files are not in a subdirectory). \throw UsageError when NAME is
//! not a single directory name (empty, `.`, `..`, or containing `/`).
std::string region_option(const Options& options);

} // namespace meshmorph::app
