// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The exit statuses of meshMorph's applications (one table: a number means the same
//! in every application) and the error handling they share.
#pragma once

#include <functional>
#include <string>

namespace meshmorph::app
{

inline constexpr int exit_ok = 0;             //!< done (checkMeshQuality: "Mesh OK.")
inline constexpr int exit_checks_failed = 1;  //!< checkMeshQuality: "Failed N mesh checks."
inline constexpr int exit_input_error = 2;    //!< bad option, dictionary, mesh or file
inline constexpr int exit_refused = 3;        //!< morphMesh: the morph would invert cells
inline constexpr int exit_fit_failed = 4;     //!< morphMesh: the deformation could not be fitted
inline constexpr int exit_internal_error = 5; //!< a bug: please report it

//! Called with the exit status and the message already logged, e.g. to write a JSON
//! report of the failure.
using FailureHook = std::function<void(int status, const std::string& message)>;

//! \brief Run an application's body and turn what it throws into an exit status and one
//! log::error message: the exception's text for UsageError and meshmorph::Error
//! (exit_input_error; SolverError exit_fit_failed), "internal error (please report it):
//! ..." for anything else (exit_internal_error).
//! \param nothing_written append the line "Nothing written." to input and fit errors
//! (morphMesh).
int run_guarded(const std::function<int()>& body, bool nothing_written,
                const FailureHook& on_failure = {});

} // namespace meshmorph::app
