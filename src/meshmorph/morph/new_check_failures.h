// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The checks a morph or a design variant makes fail that the mesh passed before:
//! found, said (a warning each) and, with morphDict `newCheckFailures refuse`, a refusal.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "meshmorph/core/types.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::io
{
class FoamDictionary;
}

namespace meshmorph::morph
{

//! Per check `after` fails and `before` passed: its name and first offender set's size.
using NewCheckFailures = std::vector<std::pair<std::string, Index>>;

NewCheckFailures new_failed_checks(const QualityReport& before, const QualityReport& after);

//! morphDict `newCheckFailures warn | refuse` (default warn). \return true for refuse.
//! \throw ParseError naming the entry for any other value.
bool read_new_check_failures(const io::FoamDictionary& dict);

//! A warning per new failure (`subject`: "the morphed mesh", "the variant"); `refuse`:
//! whether morphDict says `newCheckFailures refuse` (else the warning says how to).
void warn_new_check_failures(const NewCheckFailures& failures, const std::string& subject,
                             bool refuse);

//! The reason to refuse under `newCheckFailures refuse` ("" when `failures` is empty).
std::string new_check_failures_refusal(const NewCheckFailures& failures,
                                       const std::string& subject);

} // namespace meshmorph::morph
