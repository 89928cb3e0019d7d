// SPDX-License-Identifier: GPL-3.0-or-later
// morphMesh -variables / -variant / -variants / -sensitivity on the tutorial pipe: variants
// are linear in their amplitudes and exact, agree with a one-off morph where the method is
// linear, gradients equal central finite differences, and bad input leaves the case alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "design_pipe.h"
#include "helpers.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"
#include "morph_run.h"
#include "shipped_pipe.h"

namespace meshmorph
{
namespace
{

namespace fs = std::filesystem;
using namespace design_test;

//! The pipe's core lifted by a handle, its wall squeezed and twisted, and the inner 2x2x2
//! control points of a 4x4x4 lattice moving the wall sideways: 3 + 8 variables.
const std::string design_dict = R"dict(
boundary
{
    default { type fixed; }
    "(inlet|outlet)" { type slip; }
}
handles
{
    core { box (-0.1 -0.1 0.9) (0.1 0.1 1.1); displacement (0 0 0); }
}
designVariables
{
    lift    { handle core; vector (0 0.1 0); bounds (-3 3); })dict" +
                                std::string(wall_variables) + "}\n";

std::vector<double> amplitudes(double lift, double squeeze, double twist, double bump)
{
    std::vector<double> a{lift, squeeze, twist};
    for (int k = 0; k < 8; ++k)
        a.push_back(bump * std::sin(1.0 + k));
    return a;
}

class DesignVariables : public ::testing::Test
{
protected:
    static void SetUpTestSuite()
    {
        // One case per process: CTest runs each test in its own process, in parallel.
        dir_ = new fs::path(pipe_case("shared_" + std::to_string(::getpid()), design_dict));
        const test::MorphRun r = test::run_morph_mesh(
            {"-case", dir_->string(), "-variables", "-json", (*dir_ / "setup.json").string()});
        ASSERT_EQ(r.code, 0) << r.log;
    }
    static void TearDownTestSuite() { delete dir_; }
    static fs::path* dir_;
};
fs::path* DesignVariables::dir_ = nullptr;

TEST_F(DesignVariables, set_up_stores_one_exact_field_per_variable)
{
    const nlohmann::json j = nlohmann::json::parse(read_text(*dir_ / "setup.json"));
    ASSERT_EQ(j["variables"].size(), 11u);
    EXPECT_EQ(j["variables"][0]["name"], "lift");
    EXPECT_EQ(j["variables"][3]["name"], "bump.1.1.1.x");
    EXPECT_EQ(j["variables"][10]["name"], "bump.2.2.2.x");
    for (const auto& v : j["variables"])
        EXPECT_LT(v["relativeConstraintError"].get<double>(), 1e-10) << v["name"];
    EXPECT_TRUE(fs::exists(*dir_ / "constant/designBasis"));
}

TEST_F(DesignVariables, a_variant_is_linear_in_its_amplitudes_and_moves_the_handle_exactly)
{
    const Points x0 = points_at(*dir_, "constant");
    const std::vector<double> a = amplitudes(0.5, 0.3, 1.0, 0.05);
    const std::vector<double> b = amplitudes(-0.2, 0.1, -0.5, 0.02);
    std::vector<double> sum(a.size());
    for (std::size_t k = 0; k < a.size(); ++k)
        sum[k] = a[k] + b[k];
    const Points xa = variant_points(*dir_, a), xb = variant_points(*dir_, b),
                 xs = variant_points(*dir_, sum);
    EXPECT_LT(((xa - x0) + (xb - x0) - (xs - x0)).cwiseAbs().maxCoeff(), 1e-12);
    // Variables add up: the handle's points move by 0.5 * (0 0.1 0) more than without it,
    // exactly, on top of what the wall's variables do to them.
    std::vector<double> without = a;
    without[0] = 0.0;
    const Points x_without = variant_points(*dir_, without);
    int in_handle = 0;
    for (Index i = 0; i < x0.rows(); ++i)
        if (std::abs(x0(i, 0)) <= 0.1 && std::abs(x0(i, 1)) <= 0.1 &&
            std::abs(x0(i, 2) - 1.0) <= 0.1)
        {
            ++in_handle;
            EXPECT_NEAR(xa(i, 1) - x_without(i, 1), 0.05, 1e-12);
            EXPECT_NEAR(xa(i, 0) - x_without(i, 0), 0.0, 1e-12);
            EXPECT_NEAR(xa(i, 2) - x_without(i, 2), 0.0, 1e-12);
        }
    EXPECT_GT(in_handle, 0);
    // The squeeze's own size.
    std::vector<double> squeeze(a.size(), 0.0);
    squeeze[1] = 0.5;
    expect_wall_squeezed(x0, variant_points(*dir_, squeeze), 0.5);
}

TEST_F(DesignVariables, a_variant_of_a_translation_equals_the_one_off_morph_of_the_same_motion)
{
    // The direct RBF (779 constraints) is linear in its data: one variable at amplitude 0.7
    // and a morph of the handle moved by 0.7 (0 0.1 0) give the same points.
    const fs::path one_off = pipe_case(
        "one_off", "boundary { default { type fixed; } \"(inlet|outlet)\" { type slip; } }\n"
                   "handles { core { box (-0.1 -0.1 0.9) (0.1 0.1 1.1); displacement (0 0.07 "
                   "0); } }\n");
    const test::MorphRun r = test::run_morph_mesh({"-case", one_off.string()});
    ASSERT_EQ(r.code, 0) << r.log;
    const Points x0 = points_at(*dir_, "constant");
    const Points morphed = points_at(one_off, "1");
    const Points variant = variant_points(*dir_, amplitudes(0.7, 0, 0, 0));
    EXPECT_LT((variant - morphed).cwiseAbs().maxCoeff(), 1e-9 * 0.07);
    EXPECT_GT((variant - x0).cwiseAbs().maxCoeff(), 0.05);
}

TEST_F(DesignVariables, volume_sensitivity_equals_central_finite_differences)
{
    const io::FoamPolyMesh foam = io::read_poly_mesh(*dir_);
    const Points w = weights(foam.mesh.points);
    write_point_field(*dir_ / "0/dJdx", w, {}, foam.mesh);
    const std::vector<double> g = gradient_from(*dir_, "0/dJdx");
    ASSERT_EQ(g.size(), 11u);
    // As OpenFOAM writes a computed point field: `calculated` patches without values.
    std::string text = read_text(*dir_ / "0/dJdx");
    for (std::size_t at; (at = text.find(" value uniform (0 0 0);")) != std::string::npos;)
        text.erase(at, std::string(" value uniform (0 0 0);").size());
    test::write_text(*dir_ / "0/dJdxNoValues", text);
    EXPECT_EQ(gradient_from(*dir_, "0/dJdxNoValues"), g);
    expect_central_differences(*dir_, w, g, amplitudes(0.2, 0.1, 0.5, 0.01), {0, 1, 2, 4, 9});
}

TEST_F(DesignVariables, surface_sensitivity_on_the_wall_equals_finite_differences_of_a_wall_sum)
{
    const io::FoamPolyMesh foam = io::read_poly_mesh(*dir_);
    const PolyMesh& mesh = foam.mesh;
    std::size_t wall = 0;
    while (mesh.patches[wall].name != "wall")
        ++wall;
    const std::vector<Index> wall_points = patch_points(mesh, mesh.patches[wall]);
    const Points w = weights(mesh.points);
    Points on_wall(Index(wall_points.size()), 3);
    for (std::size_t k = 0; k < wall_points.size(); ++k)
        on_wall.row(Index(k)) = w.row(wall_points[k]);
    write_point_field(*dir_ / "0/dJdxWall", Points::Zero(mesh.n_points(), 3), {{"wall", on_wall}},
                      mesh);
    const std::vector<double> g = gradient_from(*dir_, "0/dJdxWall");
    const auto wall_sum = [&](const Points& x)
    {
        double s = 0;
        for (std::size_t k = 0; k < wall_points.size(); ++k)
            s += w.row(wall_points[k]).dot(x.row(wall_points[k]));
        return s;
    };
    const std::vector<double> a = amplitudes(0.2, 0.1, 0.5, 0.01);
    for (std::size_t j : {1u, 2u, 7u})
    {
        const double h = 1e-3;
        std::vector<double> up = a, down = a;
        up[j] += h;
        down[j] -= h;
        const double fd =
            (wall_sum(variant_points(*dir_, up)) - wall_sum(variant_points(*dir_, down))) / (2 * h);
        EXPECT_NEAR(g[j], fd, 1e-6 * std::max(1.0, std::abs(fd))) << "variable " << j;
        EXPECT_GT(std::abs(fd), 1e-3) << "variable " << j;
    }
    // The handle lies inside the pipe: it moves no wall point, so J of the wall ignores it.
    EXPECT_NEAR(g[0], 0.0, 1e-12);
}

TEST_F(DesignVariables, variants_of_a_table_go_to_their_own_time_directories_with_a_json_row_each)
{
    std::ostringstream table;
    table << "# a small design of experiments\n";
    for (int row = 0; row < 4; ++row)
    {
        const std::vector<double> a = amplitudes(0.25 * row, 0.05 * row, -0.5 * row, 0.01 * row);
        for (double v : a)
            table << v << ", ";
        table << "\n";
    }
    test::write_text(*dir_ / "doe.csv", table.str());
    const fs::path json = *dir_ / "doe.json";
    const test::MorphRun r =
        test::run_morph_mesh({"-case", dir_->string(), "-variants", (*dir_ / "doe.csv").string(),
                              "-json", json.string()});
    ASSERT_EQ(r.code, 0) << r.log;
    const nlohmann::json j = nlohmann::json::parse(read_text(json));
    EXPECT_TRUE(j["finished"].get<bool>()) << "rows are recorded as written, then the end";
    ASSERT_EQ(j["rows"].size(), 4u);
    for (int row = 0; row < 4; ++row)
    {
        const auto& v = j["rows"][std::size_t(row)];
        EXPECT_TRUE(v["valid"].get<bool>());
        EXPECT_TRUE(v["written"].get<bool>());
        EXPECT_EQ(v["outputInstance"], std::to_string(row + 1));
        EXPECT_NEAR(v["amplitudes"]["lift"].get<double>(), 0.25 * row, 1e-15);
        EXPECT_EQ(v["after"]["negativeVolumeCells"].get<int>(), 0);
        EXPECT_TRUE(fs::exists(v["path"].get<std::string>()));
    }
    for (int row = 1; row <= 4; ++row)
        fs::remove_all(*dir_ / std::to_string(row));
}

TEST_F(DesignVariables, a_variant_that_folds_cells_is_untangled_and_stays_exact)
{
    // The core lifted a little past the lift where the linear combination first folds a
    // cell (the step search finds it: 2.91 x 0.1 of the pipe's 0.5 radius), within the
    // lift's bounds (-3 3), folds a few cells around the handle; the one-off morph's
    // untangling repairs them.
    const fs::path json = *dir_ / "untangled.json";
    std::vector<double> folding = amplitudes(0.0, 0, 0, 0.01);
    const test::MorphRun search = test::run_morph_mesh(
        {"-case", dir_->string(), "-variant", amplitude_list(folding), "-direction",
         amplitude_list(amplitudes(1, 0, 0, 0)), "-json", json.string()});
    ASSERT_EQ(search.code, 0) << search.log;
    const nlohmann::json step = nlohmann::json::parse(read_text(json));
    ASSERT_EQ(step["limitedBy"], "inversion") << step.dump(1);
    folding[0] = std::min(1.03 * step["invalidAbove"].get<double>(), 3.0);
    ASSERT_GT(folding[0], step["invalidAbove"].get<double>()) << step.dump(1);
    const test::MorphRun r = test::run_morph_mesh(
        {"-case", dir_->string(), "-variant", amplitude_list(folding), "-json", json.string()});
    ASSERT_EQ(r.code, 0) << r.log;
    EXPECT_NE(r.log.find("Untangled "), std::string::npos) << r.log;
    const nlohmann::json j = nlohmann::json::parse(read_text(json));
    EXPECT_TRUE(j["valid"].get<bool>() && j["written"].get<bool>()) << j.dump(1);
    EXPECT_GT(j["untangle"]["invalidBefore"].get<int>(), 0) << j["untangle"];
    EXPECT_EQ(j["untangle"]["invalidAfter"].get<int>(), 0) << j["untangle"];
    EXPECT_GT(j["untangle"]["pointsMoved"].get<int>(), 0) << j["untangle"];
    EXPECT_LT(j["relativeConstraintError"].get<double>(), 1e-9) << j.dump(1); // handle exact
    EXPECT_EQ(j["after"]["negativeVolumeCells"].get<int>(), 0);
    EXPECT_EQ(j["after"]["incorrectlyOrientedFacePyramids"].get<int>(), 0);
    fs::remove_all(*dir_ / "1");
    // With fewer cells allowed than it needs, refused without trying; the set-up stays
    // current (the key judges variants only).
    const std::string dict = read_text(*dir_ / "system/morphDict");
    test::write_text(*dir_ / "system/morphDict", dict + "maxUntangleCells 0;\n");
    const test::MorphRun capped = test::run_morph_mesh(
        {"-case", dir_->string(), "-variant", amplitude_list(folding), "-json", json.string()});
    test::write_text(*dir_ / "system/morphDict", dict);
    EXPECT_EQ(capped.code, 3) << capped.log;
    EXPECT_EQ(capped.log.find("Untangled "), std::string::npos) << capped.log;
    const std::string skipped =
        nlohmann::json::parse(read_text(json))["untangle"]["skipped"].get<std::string>();
    EXPECT_NE(skipped.find("more than maxUntangleCells 0"), std::string::npos) << skipped;
    EXPECT_FALSE(fs::exists(*dir_ / "1"));
}

TEST_F(DesignVariables, a_variant_folding_too_many_cells_to_untangle_is_refused_at_once)
{
    // The lift above with the wall squeezed by 80% of its radius onto the core: 40% of the
    // cells fold, far more than a local repair is for. Refused without trying, naming the
    // variable to back off.
    const fs::path json = *dir_ / "refused.json";
    const test::MorphRun r = test::run_morph_mesh({"-case", dir_->string(), "-variant",
                                                   amplitude_list(amplitudes(3.0, 8.0, 0, 0.01)),
                                                   "-json", json.string()});
    if (r.code == 0)
        GTEST_FAIL() << "expected a refusal\n" << r.log;
    EXPECT_EQ(r.code, 3) << r.log;
    EXPECT_EQ(r.log.find("Untangled "), std::string::npos) << r.log;
    const nlohmann::json j = nlohmann::json::parse(read_text(json));
    EXPECT_FALSE(j["written"].get<bool>());
    const std::string skipped = j["untangle"]["skipped"].get<std::string>();
    EXPECT_NE(skipped.find("more than 5% of the 2240 cells"), std::string::npos) << skipped;
    EXPECT_NE(j["refusal"].get<std::string>().find("not untangled"), std::string::npos);
    // Where: the squeezed wall's cells among them.
    EXPECT_GT(j["invalidCellsByPatch"].value("wall", 0), 0) << j["invalidCellsByPatch"];
    EXPECT_NE(j["refusal"].get<std::string>().find("in cells touching "), std::string::npos)
        << j["refusal"];
    // (Without the lift, the squeeze alone is valid: a scaling about the axis.)
    EXPECT_EQ(j["backOff"].get<std::string>().rfind("lift", 0), 0u) << j["backOff"];
    EXPECT_NE(r.log.find("back off lift"), std::string::npos) << r.log;
    EXPECT_FALSE(fs::exists(*dir_ / "1"));
}

TEST_F(DesignVariables, a_variant_failing_a_check_the_mesh_passed_is_said_and_refused_on_request)
{
    // The wall squeezed to 0.5% of its radius (amplitude 9.95 of 10% each): the RBF
    // reproduces the scaling about the axis, so every cell is valid and 200 times thinner,
    // and the aspect ratio passes checkMesh's limit of 1000 (the pipe's is 8.2).
    const fs::path json = *dir_ / "aspect.json";
    const std::vector<std::string> args{"-case",    dir_->string(),
                                        "-variant", amplitude_list(amplitudes(0, 9.95, 0, 0)),
                                        "-json",    json.string()};
    const test::MorphRun warned = test::run_morph_mesh(args);
    ASSERT_EQ(warned.code, 0) << warned.log;
    EXPECT_NE(warned.err.find("Warning: the variant fails the check aspectRatio"),
              std::string::npos)
        << warned.err;
    nlohmann::json j = nlohmann::json::parse(read_text(json));
    ASSERT_EQ(j["newFailedChecks"].size(), 1u) << j.dump(1);
    EXPECT_EQ(j["newFailedChecks"][0]["check"], "aspectRatio");
    EXPECT_GT(j["newFailedChecks"][0]["count"].get<int>(), 0);
    EXPECT_TRUE(j["written"].get<bool>());
    fs::remove_all(*dir_ / "1");
    // `newCheckFailures refuse` makes it an error, and leaves the set-up current.
    const std::string dict = read_text(*dir_ / "system/morphDict");
    test::write_text(*dir_ / "system/morphDict", dict + "newCheckFailures refuse;\n");
    const test::MorphRun refused = test::run_morph_mesh(args);
    test::write_text(*dir_ / "system/morphDict", dict);
    EXPECT_EQ(refused.code, 3) << refused.log;
    j = nlohmann::json::parse(read_text(json));
    EXPECT_FALSE(j["written"].get<bool>());
    EXPECT_NE(j["refusal"].get<std::string>().find("aspectRatio"), std::string::npos) << j;
    EXPECT_FALSE(fs::exists(*dir_ / "1"));
    // maxNonOrtho is read by a one-off morph only: editing it leaves the set-up current too.
    test::write_text(*dir_ / "system/morphDict", dict + "maxNonOrtho 60;\n");
    const test::MorphRun edited = test::run_morph_mesh(args);
    test::write_text(*dir_ / "system/morphDict", dict);
    EXPECT_EQ(edited.code, 0) << edited.log;
    EXPECT_TRUE(fs::exists(*dir_ / "1"));
    fs::remove_all(*dir_ / "1");
}

TEST_F(DesignVariables, a_step_search_finds_the_largest_valid_lift_and_the_check_confirms_it)
{
    // From a small design, along the lift (bounded by 3; cells fold before: the test above).
    const std::vector<double> start = amplitudes(0.2, 0.1, 0.5, 0.01);
    const fs::path json = *dir_ / "step.json";
    const test::MorphRun r = test::run_morph_mesh(
        {"-case", dir_->string(), "-variant", amplitude_list(start), "-direction",
         amplitude_list(amplitudes(1, 0, 0, 0)), "-json", json.string()});
    ASSERT_EQ(r.code, 0) << r.log;
    EXPECT_NE(r.log.find("Largest valid step: "), std::string::npos) << r.log;
    EXPECT_FALSE(fs::exists(*dir_ / "1")) << "a step search writes no mesh";
    const nlohmann::json j = nlohmann::json::parse(read_text(json));
    ASSERT_EQ(j["limitedBy"], "inversion") << j.dump(1);
    const double t = j["step"].get<double>(), above = j["invalidAbove"].get<double>();
    EXPECT_GT(t, 0.0);
    EXPECT_LT(start[0] + t, 3.0);
    EXPECT_LE((above - t) / above, 1.0001e-4) << j.dump(1); // the bracket's width
    EXPECT_NEAR(j["estimate"].get<double>() / t, 1.0, 0.02) << j.dump(1);
    // The linear combination at the step is valid; just above it, it folds cells (which
    // -variant then untangles).
    std::vector<double> at = start, beyond = start;
    at[0] += t;
    beyond[0] += above;
    const fs::path variant_json = *dir_ / "step_variant.json";
    for (const auto& [a, folds] : {std::pair{at, false}, std::pair{beyond, true}})
    {
        const test::MorphRun v =
            test::run_morph_mesh({"-case", dir_->string(), "-variant", amplitude_list(a), "-json",
                                  variant_json.string()});
        EXPECT_EQ(v.code, 0) << v.log;
        const nlohmann::json vj = nlohmann::json::parse(read_text(variant_json));
        EXPECT_EQ(vj.contains("untangle"), folds) << vj.dump(1);
        if (folds && vj.contains("untangle"))
        {
            EXPECT_GT(vj["untangle"]["invalidBefore"].get<int>(), 0);
        }
        fs::remove_all(*dir_ / "1");
    }
    // -stepLimit below the inversion is the answer; -direction needs -variant.
    const test::MorphRun limited = test::run_morph_mesh(
        {"-case", dir_->string(), "-variant", amplitude_list(start), "-direction",
         amplitude_list(amplitudes(1, 0, 0, 0)), "-stepLimit", "0.25", "-json", json.string()});
    ASSERT_EQ(limited.code, 0) << limited.log;
    EXPECT_EQ(nlohmann::json::parse(read_text(json))["step"].get<double>(), 0.25);
    EXPECT_EQ(nlohmann::json::parse(read_text(json))["limitedBy"], "limit");
    // A non-orthogonality limit below the start's maximum is refused, saying so.
    const test::MorphRun strict = test::run_morph_mesh(
        {"-case", dir_->string(), "-variant", amplitude_list(start), "-direction",
         amplitude_list(amplitudes(1, 0, 0, 0)), "-maxNonOrtho", "1"});
    EXPECT_EQ(strict.code, 2) << strict.log;
    EXPECT_NE(strict.log.find("already above the limit of 1 degrees"), std::string::npos)
        << strict.log;
    const test::MorphRun alone = test::run_morph_mesh(
        {"-case", dir_->string(), "-direction", amplitude_list(amplitudes(1, 0, 0, 0))});
    EXPECT_EQ(alone.code, 2) << alone.log;
    EXPECT_FALSE(fs::exists(*dir_ / "1"));
    EXPECT_NE(alone.log.find("-direction goes with -variant"), std::string::npos) << alone.log;
}

TEST_F(DesignVariables, bad_amplitudes_and_foreign_files_are_refused_and_leave_the_case_alone)
{
    const auto refused = [&](const std::vector<std::string>& args, const std::string& words)
    {
        std::vector<std::string> all{"-case", dir_->string()};
        all.insert(all.end(), args.begin(), args.end());
        const test::MorphRun r = test::run_morph_mesh(all);
        EXPECT_EQ(r.code, 2) << r.log;
        EXPECT_NE(r.log.find(words), std::string::npos) << "expected '" << words << "' in\n"
                                                        << r.log;
        EXPECT_FALSE(fs::exists(*dir_ / "1"));
    };
    refused({"-variant", "(1 2)"}, "2 amplitudes given, the set-up has 11 design variables");
    refused({"-variant", amplitude_list(amplitudes(5, 0, 0, 0))},
            "the amplitude 5 of lift is outside its bounds (-3 3)");
    refused({"-variant", "(1 x 2)"}, "'x' is not a finite number");
    refused({"-variants", (*dir_ / "missing.csv").string()}, "missing.csv");
    // A row out of bounds is named by its number; a header by the column that differs.
    const std::string zero = amplitude_list(amplitudes(0, 0, 0, 0));
    test::write_text(
        *dir_ / "bounds.csv", zero.substr(1, zero.size() - 2) + "\n" +
                                  [&]
                                  {
                                      const std::string a = amplitude_list(amplitudes(5, 0, 0, 0));
                                      return a.substr(1, a.size() - 2);
                                  }() +
                                  "\n");
    refused({"-variants", (*dir_ / "bounds.csv").string()}, "bounds.csv: row 2");
    test::write_text(*dir_ / "header.csv", "lift nope\n0 0\n");
    refused({"-variants", (*dir_ / "header.csv").string()}, "column 2 is 'nope'");
    // A sensitivity of another mesh (the wrong number of points).
    test::write_text(*dir_ / "0/otherMesh",
                     "FoamFile { version 2.0; format ascii; class pointVectorField; object "
                     "otherMesh; }\ndimensions [0 0 0 0 0 0 0];\ninternalField nonuniform "
                     "List<vector> 2((0 0 0)(1 1 1));\nboundaryField { \".*\" { type calculated; "
                     "value uniform (0 0 0); } }\n");
    refused({"-sensitivity", "0/otherMesh"}, "otherMesh");
    // OpenFOAM's default normal sensitivity (a density, not dJ/dx).
    test::write_text(*dir_ / "0/pointSensNormal",
                     "FoamFile { version 2.0; format ascii; class pointScalarField; object "
                     "pointSensNormal; }\ndimensions [0 0 0 0 0 0 0];\ninternalField uniform 0;\n"
                     "boundaryField { \".*\" { type calculated; } }\n");
    refused({"-sensitivity", "0/pointSensNormal"}, "includeSurfaceArea true");
    refused({"-variant", "(1)", "-variables"}, "mutually exclusive");
}

TEST(DesignVariableSetUp, a_stale_or_foreign_set_up_is_refused)
{
    const fs::path dir = pipe_case("stale", design_dict);
    ASSERT_EQ(test::run_morph_mesh({"-case", dir.string(), "-variables"}).code, 0);
    const std::string a = amplitude_list(amplitudes(0.1, 0, 0, 0));
    // A comment added to the dictionary changes nothing; an edited value makes it stale.
    std::ofstream(dir / "system/morphDict", std::ios::app) << "// a comment\n";
    test::MorphRun r = test::run_morph_mesh({"-case", dir.string(), "-variant", a});
    EXPECT_EQ(r.code, 0) << r.log;
    fs::remove_all(dir / "1");
    std::string text = read_text(dir / "system/morphDict");
    text.replace(text.find("vector (0 0.1 0)"), 16, "vector (0 0.2 0)");
    test::write_text(dir / "system/morphDict", text);
    r = test::run_morph_mesh({"-case", dir.string(), "-variant", a});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.log.find("was made for another version of"), std::string::npos) << r.log;
    // Another mesh's points.
    ASSERT_EQ(test::run_morph_mesh({"-case", dir.string(), "-variables"}).code, 0);
    io::FoamPolyMesh foam = io::read_poly_mesh(dir);
    foam.mesh.points(0, 0) += 1e-9;
    io::write_poly_mesh(foam.mesh, io::default_poly_mesh_files(io::FoamFormat::binary), dir,
                        "constant");
    r = test::run_morph_mesh({"-case", dir.string(), "-variant", a});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.log.find("was made for other points"), std::string::npos) << r.log;
    // A truncated set-up, and not a set-up at all.
    ASSERT_EQ(test::run_morph_mesh({"-case", dir.string(), "-variables"}).code, 0);
    fs::resize_file(dir / "constant/designBasis", fs::file_size(dir / "constant/designBasis") - 8);
    r = test::run_morph_mesh({"-case", dir.string(), "-variant", a});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.log.find("truncated at the block of bump.2.2.2.x"), std::string::npos) << r.log;
    test::write_text(dir / "constant/designBasis", "solid foo\n");
    r = test::run_morph_mesh({"-case", dir.string(), "-variant", a});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.log.find("not a meshMorph design set-up"), std::string::npos) << r.log;
    EXPECT_FALSE(fs::exists(dir / "1"));
}

TEST(DesignVariableSetUp, a_handle_rotated_and_scaled_moves_by_the_linearised_motion)
{
    const fs::path dir =
        pipe_case("handle_motions",
                  "boundary { default { type fixed; } }\n"
                  "handles { core { box (-0.1 -0.1 0.9) (0.1 0.1 1.1); displacement (0 0 0); } }\n"
                  "designVariables {\n"
                  "  spin { handle core; type rotate; origin (0 0 1); axis (1 0 0); angle 10; }\n"
                  "  grow { handle core; type scale; origin (0 0 1); factor 1.2; }\n}\n");
    ASSERT_EQ(test::run_morph_mesh({"-case", dir.string(), "-variables"}).code, 0);
    const test::MorphRun r = test::run_morph_mesh({"-case", dir.string(), "-variant", "(0.5 1)"});
    ASSERT_EQ(r.code, 0) << r.log;
    const Points x0 = points_at(dir, "constant"), x = points_at(dir, "1");
    const double theta = 0.5 * 10.0 * M_PI / 180.0;
    int in_handle = 0;
    for (Index i = 0; i < x0.rows(); ++i)
    {
        const Vector3 p = x0.row(i).transpose(), c(0, 0, 1);
        if ((p - c).cwiseAbs().maxCoeff() > 0.1)
            continue;
        ++in_handle;
        const Vector3 expected = theta * Vector3::UnitX().cross(p - c) + 0.2 * (p - c);
        EXPECT_LT((x.row(i).transpose() - p - expected).norm(), 1e-12) << "point " << i;
    }
    EXPECT_GT(in_handle, 8);
}

TEST(DesignVariableSetUp, dmffd_targets_are_design_variables_too)
{
    // DM-FFD with handle targets (the paper's direct manipulation) as variables: a least-
    // squares fit of the lattice, so the targets are met as closely as the lattice allows.
    const fs::path dir = pipe_case(
        "dmffd", "method dmffd;\ndmffd { lattice (8 8 8); }\n"
                 "boundary { default { type fixed; } }\n"
                 "handles { core { box (-0.1 -0.1 0.9) (0.1 0.1 1.1); displacement (0 0 0); } }\n"
                 "designVariables { lift { handle core; vector (0 0.05 0); } }\n");
    const fs::path json = dir / "variant.json";
    ASSERT_EQ(test::run_morph_mesh({"-case", dir.string(), "-variables"}).code, 0);
    const test::MorphRun r =
        test::run_morph_mesh({"-case", dir.string(), "-variant", "(1)", "-json", json.string()});
    ASSERT_EQ(r.code, 0) << r.log;
    const nlohmann::json j = nlohmann::json::parse(read_text(json));
    EXPECT_NEAR(j["maxPrescribedDisplacement"].get<double>(), 0.05, 1e-12);
    EXPECT_LT(j["relativeConstraintError"].get<double>(), 0.5) << "the lattice follows the target";
    EXPECT_GT(j["maxDisplacement"].get<double>(), 0.01);
}

//! A 2D channel (nx x 4 x 1 cells over x in [0, length], y in [0, 0.4], z in [0, 0.1]; zMin
//! and zMax empty, yMin and yMax walls) whose floor (yMin) the lattice variable `floor` moves:
//! `lattice` holds its entries after `type ffd; patches (yMin);`. Returns the case directory.
fs::path channel_with_a_floor_lattice(const std::string& name, int nx, double length,
                                      const std::string& lattice)
{
    const fs::path dir = test::scratch_dir("design_variables/" + name);
    const PolyMesh mesh = test::make_block_mesh(
        nx, 4, 1,
        [length](double u, double v, double w) { return Vector3(length * u, 0.4 * v, 0.1 * w); },
        {"patch", "patch", "wall", "wall", "empty", "empty"});
    io::write_poly_mesh(mesh, io::default_poly_mesh_files(io::FoamFormat::binary), dir, "constant");
    fs::create_directories(dir / "system");
    fs::copy_file(test::pipe_tutorial_dir() / "system/controlDict", dir / "system/controlDict");
    test::write_text(dir / "system/morphDict",
                     "FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }\n"
                     "boundary { default { type fixed; } }\n"
                     "designVariables { floor { type ffd; patches (yMin); " +
                         lattice + " } }\n");
    return dir;
}

TEST(DesignVariableSetUp, a_2d_lattice_moves_both_empty_planes_alike)
{
    // A 2D channel (one cell thick, zMin and zMax empty) whose bottom wall is moved by a
    // lattice that does not vary along z (`lattice (5 4 1)`): the case stays 2D.
    const fs::path dir =
        channel_with_a_floor_lattice("two_d", 10, 1.0,
                                     "lattice (5 4 1);\n  box ((-0.1 -0.1 -0.5) (1.1 0.5 0.6)); "
                                     "directions (y); confine (1 1 0);");
    const test::MorphRun set_up = test::run_morph_mesh({"-case", dir.string(), "-variables"});
    ASSERT_EQ(set_up.code, 0) << set_up.log;
    EXPECT_NE(set_up.log.find("Variable floor.2.1.0.y"), std::string::npos) << set_up.log;
    const test::MorphRun r =
        test::run_morph_mesh({"-case", dir.string(), "-variant", "(0.02 0.03 0.02 0 0 0)"});
    ASSERT_EQ(r.code, 0) << r.log;
    const Points x0 = points_at(dir, "constant"), x = points_at(dir, "1");
    double largest = 0.0;
    for (Index i = 0; i < x0.rows(); ++i)
        for (Index j = 0; j < x0.rows(); ++j)
            if (x0(i, 2) == 0.0 && x0(j, 2) > 0.0 && x0(i, 0) == x0(j, 0) && x0(i, 1) == x0(j, 1))
            {
                EXPECT_EQ(x(i, 0) - x0(i, 0), x(j, 0) - x0(j, 0)) << "points " << i << ", " << j;
                EXPECT_EQ(x(i, 1) - x0(i, 1), x(j, 1) - x0(j, 1)) << "points " << i << ", " << j;
                EXPECT_EQ(x(i, 2), x0(i, 2));
                EXPECT_EQ(x(j, 2), x0(j, 2));
                largest = std::max(largest, std::abs(x(i, 1) - x0(i, 1)));
            }
    EXPECT_GT(largest, 1e-3) << "the floor moves";
}

//! A 2D channel over x in [0, 2] whose floor a lattice over x in [0.5, 1.5] moves,
//! `confine (c 0 0)`; returns the case directory.
fs::path channel_with_a_lattice_cutting_its_floor(const std::string& name, int confine)
{
    return channel_with_a_floor_lattice(name, 20, 2.0,
                                        "lattice (7 4 1);\n  box ((0.5 -0.1 -0.5) (1.5 0.5 0.6)); "
                                        "directions (y); confine (" +
                                            std::to_string(confine) + " 0 0);");
}

//! The largest |y-displacement| of the floor's points at x = 0.5 and 1.5 (the box's faces)
//! after a variant with every amplitude 0.01.
double floor_motion_at_the_box_faces(const fs::path& dir, std::size_t n_variables)
{
    std::string amplitudes = "(";
    for (std::size_t j = 0; j < n_variables; ++j)
        amplitudes += " 0.01";
    const test::MorphRun r =
        test::run_morph_mesh({"-case", dir.string(), "-variant", amplitudes + " )"});
    EXPECT_EQ(r.code, 0) << r.log;
    const Points x0 = points_at(dir, "constant"), x = points_at(dir, "1");
    double largest = 0.0;
    for (Index i = 0; i < x0.rows(); ++i)
        if (x0(i, 1) == 0.0 &&
            (std::abs(x0(i, 0) - 0.5) < 1e-12 || std::abs(x0(i, 0) - 1.5) < 1e-12))
            largest = std::max(largest, std::abs(x(i, 1) - x0(i, 1)));
    return largest;
}

TEST(DesignVariableSetUp, a_lattice_box_cutting_its_walls_without_confine_3_is_said_and_steps_them)
{
    // The uniform cubic lattice's box faces carry (P0 + 4 P1 + P2) / 6 of the outer layers:
    // with 2 held, 1/6 of the third layer's motion, and the floor just outside the box does
    // not move: a step, said at -variables. With 3 held the motion fades to zero at the face.
    const fs::path two = channel_with_a_lattice_cutting_its_floor("box_cut_2", 2);
    const test::MorphRun said = test::run_morph_mesh({"-case", two.string(), "-variables"});
    ASSERT_EQ(said.code, 0) << said.log;
    EXPECT_NE(said.err.find("Warning: designVariables floor (line 3): its box cuts the patches "
                            "it moves across x"),
              std::string::npos)
        << said.err;
    EXPECT_NE(said.err.find("up to 1/6 of a control point's motion"), std::string::npos)
        << said.err;
    EXPECT_NE(said.err.find("confine 3 along x"), std::string::npos) << said.err;
    EXPECT_EQ(said.err.find("across y"), std::string::npos) << "the box holds the floor in y";
    // 3 free layers in x (2, 3, 4) x 4 in y (their weights sum to 1), moving in y: the face
    // moves 0.01 / 6.
    EXPECT_NEAR(floor_motion_at_the_box_faces(two, 12), 0.01 / 6.0, 1e-12);

    const fs::path three = channel_with_a_lattice_cutting_its_floor("box_cut_3", 3);
    const test::MorphRun quiet = test::run_morph_mesh({"-case", three.string(), "-variables"});
    ASSERT_EQ(quiet.code, 0) << quiet.log;
    EXPECT_EQ(quiet.err.find("its box cuts"), std::string::npos) << quiet.err;
    EXPECT_LT(floor_motion_at_the_box_faces(three, 4), 1e-15);
}

TEST(DesignVariableSetUp, a_moving_boundary_entry_and_a_surface_variable_are_refused_by_name)
{
    const fs::path moving = pipe_case(
        "moving", "boundary { wall { type translate; vector (0 0.1 0); } }\n"
                  "designVariables { s { patches (inlet); type translate; vector (1 0 0); } }\n");
    test::MorphRun r = test::run_morph_mesh({"-case", moving.string(), "-variables"});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.log.find("boundary entry wall has type translate"), std::string::npos) << r.log;
    const fs::path surface = pipe_case(
        "surface", "designVariables { s { patches (wall); type surface; file \"x.stl\"; } }\n");
    r = test::run_morph_mesh({"-case", surface.string(), "-variables"});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.log.find("type surface is not a design variable"), std::string::npos) << r.log;
    EXPECT_FALSE(fs::exists(surface / "constant/designBasis"));
}

} // namespace
} // namespace meshmorph
