// SPDX-License-Identifier: GPL-3.0-or-later
// The two sides of a cyclic patch move alike (morph/cyclic_coupling.h), on OpenFOAM's
// periodic column (boundaryWallFunctions: cyclic front/back, walls top and bottom, 2D).
#include <gtest/gtest.h>

#include "helpers.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/morph/cyclic_coupling.h"
#include "morph_run.h"
#include "openfoam_cases.h"

namespace meshmorph
{
namespace
{

namespace fs = std::filesystem;

//! A copy of the periodic column with `boundary` as the morphDict's boundary entries and
//! `handles` as its handles.
fs::path column_case(const std::string& name, const std::string& boundary,
                     const std::string& handles = "")
{
    const fs::path dir = test::scratch_dir("cyclic_morph/" + name);
    fs::copy(test::openfoam_case("cyclic-column"), dir, fs::copy_options::recursive);
    test::write_text(dir / "system/morphDict",
                     "FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }\n"
                     "method rbf;\nconflicts last;\nboundary\n{\n" +
                         boundary + "}\n" +
                         (handles.empty() ? "" : "handles\n{\n" + handles + "}\n"));
    return dir;
}

//! The largest difference of the displacements of cyclic partners after the morph.
double largest_partner_difference(const fs::path& dir)
{
    const io::FoamPolyMesh foam = io::read_poly_mesh(dir);
    const Points moved = io::read_points_file(dir / "1/polyMesh/points");
    const Points d = moved - foam.mesh.points;
    double largest = 0;
    const std::vector<morph::CyclicPointPair> pairs = morph::cyclic_point_pairs(foam.mesh);
    EXPECT_FALSE(pairs.empty());
    for (const morph::CyclicPointPair& p : pairs)
        largest = std::max(
            largest,
            (d.row(p.partner).transpose() - p.to_partner * d.row(p.point).transpose()).norm());
    return largest;
}

#define REQUIRE_OPENFOAM()                                                                         \
    if (!test::openfoam_available())                                                               \
    GTEST_SKIP() << "OpenFOAM not installed: the periodic column is made by blockMesh"

TEST(CyclicMorph, free_cyclic_sides_get_the_same_displacement)
{
    REQUIRE_OPENFOAM();
    // A handle on the front side only: the field differs across the column (uncoupled, the
    // partners moved 2e-7 apart); the back partner of each handle point follows it, and the
    // free pairs are averaged.
    const fs::path dir = column_case(
        "free", "wall { type fixed; }\n\"(front|back)\" { type free; }\n",
        "core { box (-0.0001 -0.013 -1) (0.0001 -0.012 1); displacement (0.001 0.002 0); }\n");
    const test::MorphRun r = test::run_morph_mesh({"-case", dir.string()});
    ASSERT_EQ(r.code, 0) << r.log;
    EXPECT_NE(r.log.find("Constraints: 12 prescribed points"), std::string::npos) << r.log;
    EXPECT_LT(largest_partner_difference(dir), 1e-15);
}

TEST(CyclicMorph, one_moving_side_moves_its_partner)
{
    REQUIRE_OPENFOAM();
    // The walls come last: they win the edge points on both sides (conflicts last), so
    // the prescriptions stay periodic there; the rest of back follows front.
    const fs::path dir = column_case("one_side", "front { type translate; vector (0 0.001 0); }\n"
                                                 "back { type free; }\nwall { type fixed; }\n");
    const test::MorphRun r = test::run_morph_mesh({"-case", dir.string(), "-force"});
    ASSERT_EQ(r.code, 0) << r.log;
    EXPECT_LT(largest_partner_difference(dir), 1e-15);
}

TEST(CyclicMorph, sides_prescribed_differently_are_refused_naming_the_patch)
{
    REQUIRE_OPENFOAM();
    const fs::path dir = column_case("differ", "front { type translate; vector (0 0.001 0); }\n"
                                               "back { type translate; vector (0 0.002 0); }\n"
                                               "wall { type fixed; }\n");
    const test::MorphRun r = test::run_morph_mesh({"-case", dir.string()});
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_NE(r.err.find("cyclic patch front"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("must move alike"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "1"));
}

} // namespace
} // namespace meshmorph
