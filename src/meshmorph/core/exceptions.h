// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The few exception types of meshmorph; the library never exits or prints errors.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace meshmorph
{

//! Base of every error meshmorph throws.
class Error : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

//! A file could not be opened, read or written.
class IoError : public Error
{
public:
    using Error::Error;
};

//! Malformed file content. what() reads "path:line: message" (line 0: "path: message").
class ParseError : public Error
{
public:
    ParseError(std::string path, std::size_t line, const std::string& message)
        : Error(format(path, line, message)), path_(std::move(path)), line_(line), message_(message)
    {
    }
    const std::string& path() const { return path_; }
    std::size_t line() const { return line_; }
    //! The message without the "path:line: " prefix.
    const std::string& message() const { return message_; }

private:
    static std::string format(const std::string& path, std::size_t line, const std::string& m)
    {
        if (line == 0)
            return path + ": " + m;
        return path + ":" + std::to_string(line) + ": " + m;
    }
    std::string path_;
    std::size_t line_;
    std::string message_;
};

//! Arguments that violate a documented precondition (sizes, NaN, empty input, ...).
class InvalidInput : public Error
{
public:
    using Error::Error;
};

//! A numerical solve failed (singular or too ill-conditioned system).
class SolverError : public Error
{
public:
    using Error::Error;
};

} // namespace meshmorph
