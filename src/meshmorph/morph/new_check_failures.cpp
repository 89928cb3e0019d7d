// SPDX-License-Identifier: GPL-3.0-or-later
// The checks a morph or a variant makes fail: found, warned about, refused on request.
#include "meshmorph/morph/new_check_failures.h"

#include <algorithm>

#include "meshmorph/core/log.h"
#include "meshmorph/io/foam_dictionary.h"

namespace meshmorph::morph
{

NewCheckFailures new_failed_checks(const QualityReport& before, const QualityReport& after)
{
    NewCheckFailures out;
    for (const CheckResult& c : after.checks)
    {
        if (!c.failed() ||
            std::find(before.failed_check_names.begin(), before.failed_check_names.end(),
                      c.failure) != before.failed_check_names.end())
            continue;
        out.emplace_back(c.failure, c.sets.empty() ? Index(0) : c.sets.front().size());
    }
    return out;
}

bool read_new_check_failures(const io::FoamDictionary& dict)
{
    const io::FoamEntry* e = dict.find("newCheckFailures");
    if (e == nullptr)
        return false;
    const std::vector<io::FoamValueToken>& t = e->tokens();
    if (t.size() == 1 && t[0].is_word() && (t[0].text == "warn" || t[0].text == "refuse"))
        return t[0].text == "refuse";
    throw e->error("expected 'warn' (the default: a warning per check the morph makes fail) or "
                   "'refuse' (such a morph is refused, nothing written)");
}

void warn_new_check_failures(const NewCheckFailures& failures, const std::string& subject,
                             bool refuse)
{
    for (const auto& [name, count] : failures)
        log::warning() << subject << " fails the check " << name
                       << (count > 0 ? " (" + std::to_string(count) + " offenders)" : std::string())
                       << ", which the unmorphed mesh passed: OpenFOAM's checkMesh will fail it "
                          "too"
                       << (refuse ? std::string()
                                  : " (morphDict 'newCheckFailures refuse;' makes this an error)");
}

std::string new_check_failures_refusal(const NewCheckFailures& failures, const std::string& subject)
{
    std::string list;
    for (const auto& failure : failures)
        list += (list.empty() ? "" : ", ") + failure.first;
    if (list.empty())
        return {};
    return subject + " fails checks the mesh passed before (" + list +
           ") and the morphDict says 'newCheckFailures refuse'";
}

} // namespace meshmorph::morph
