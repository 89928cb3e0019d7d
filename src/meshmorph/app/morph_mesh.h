// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The morphMesh application: its options, its JSON document and the entry point. The
//! morph itself is a library call, morph::morph_case (morph/morph_case.h).
#pragma once

#include <iosfwd>
#include <string>

#include "meshmorph/app/exit_status.h"
#include "meshmorph/morph/morph_case.h"

namespace meshmorph::app
{

//! The `-json` document: method, constraints, centres, maxConstraintError, timings
//! {read, fit, evaluate, check, write}, before, after (the checker's keys), plus
//! relativeConstraintError, conflicts, handlePoints, slipPoints, outputInstance, written,
//! refused.
std::string morph_json(const morph::MorphResult& result, int exit_status);

//! \brief The morphMesh application (argv[0] = program name): options, banner, morph_case,
//! summary. Report to `out`; the log, for the length of the run, to
//! log::stream_sink(out, err) (info on `out`, warnings and errors on `err`). Returns an exit
//! status; never throws.
int run_morph_mesh(int argc, const char* const argv[], std::ostream& out, std::ostream& err);

} // namespace meshmorph::app
