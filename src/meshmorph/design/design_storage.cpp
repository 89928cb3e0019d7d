// SPDX-License-Identifier: GPL-3.0-or-later
// morphDict `designBasis`.
#include "meshmorph/design/design_storage.h"

#include "meshmorph/io/foam_dictionary.h"

namespace meshmorph::design
{

DesignStorage read_design_storage(const io::FoamDictionary& dict)
{
    const io::FoamEntry* e = dict.find("designBasis");
    if (e == nullptr)
        return DesignStorage::fields;
    const std::vector<io::FoamValueToken>& t = e->tokens();
    if (t.size() == 1 && t[0].is_word())
    {
        if (t[0].text == "auto")
            return DesignStorage::automatic;
        if (t[0].text == "fields")
            return DesignStorage::fields;
        if (t[0].text == "shared")
            return DesignStorage::shared;
    }
    throw e->error("expected 'fields' (the default: a fit and a stored field per variable), "
                   "'shared' (one fit for every variable, held) or 'auto' (shared above " +
                   std::to_string(shared_above) + " moving variables)");
}

std::string to_string(DesignStorage storage)
{
    switch (storage)
    {
    case DesignStorage::fields:
        return "fields";
    case DesignStorage::shared:
        return "shared";
    default:
        return "auto";
    }
}

} // namespace meshmorph::design
