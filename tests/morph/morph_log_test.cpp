// SPDX-License-Identifier: GPL-3.0-or-later
// What a morph tells the user about its field (src/meshmorph/morph/morph_log.*).
#include "meshmorph/morph/morph_log.h"

#include <string>

#include <gtest/gtest.h>

#include "meshmorph/core/log.h"

namespace meshmorph::morph
{
namespace
{

//! The log of a morph whose points moved up to 1.31 times its largest prescription (as the
//! untangling of the windAroundBuildings tutorial's buildings moved 5 m sideways did).
std::string fit_log(const DeformationSettings& settings)
{
    MorphResult result;
    result.morph.max_prescribed = 5.0;
    result.max_displacement = 6.55;
    result.morph.report.method = "greedy-rbf+idw";
    const log::CaptureScope capture;
    log_fit(result, settings, 100);
    return capture.text();
}

} // namespace

TEST(MorphLog, warns_of_an_overshoot_only_where_the_field_is_not_bounded_by_construction)
{
    DeformationSettings rbf; // limit yes: the field stays within 5
    EXPECT_EQ(fit_log(rbf).find("overshoots"), std::string::npos) << fit_log(rbf);
    DeformationSettings idw;
    idw.method = DeformationMethod::idw;
    EXPECT_EQ(fit_log(idw).find("overshoots"), std::string::npos) << fit_log(idw);

    DeformationSettings unlimited;
    unlimited.limit = false;
    const std::string text = fit_log(unlimited);
    EXPECT_NE(text.find("Warning: points away from the constraints move up to 1.31 times the "
                        "largest prescribed displacement (the rbf field overshoots): rbf { "
                        "limit yes; }"),
              std::string::npos)
        << text;
    DeformationSettings dmffd;
    dmffd.method = DeformationMethod::dmffd;
    EXPECT_NE(fit_log(dmffd).find("(the dmffd field overshoots)"), std::string::npos)
        << fit_log(dmffd);
}

} // namespace meshmorph::morph
