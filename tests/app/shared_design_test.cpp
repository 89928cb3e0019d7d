// SPDX-License-Identifier: GPL-3.0-or-later
// morphDict `designBasis shared` on the tutorial pipe: one fit for every variable, held. Its
// variants are linear in their amplitudes and exact at the constrained points, its
// gradients equal central finite differences, its file holds prescriptions only, and where
// the variables cannot share a fit the set-up says why (auto) or refuses (shared).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "design_pipe.h"

namespace meshmorph
{
namespace
{

namespace fs = std::filesystem;
using namespace design_test;

//! The pipe's wall squeezed and twisted and the inner 2x2x2 control points of a 4x4x4
//! lattice moving it sideways (10 variables, no handle: they all constrain the same
//! points), with the greedy RBF so that the held choices are its centres and jump marks.
std::string shared_dict(const std::string& storage)
{
    return R"dict(
method rbf;
rbf { greedy { tolerance 1e-3; } }
designBasis )dict" +
           storage + R"dict(;
boundary
{
    default { type fixed; }
    "(inlet|outlet)" { type slip; }
}
designVariables
{)dict" + std::string(wall_variables) +
           "}\n";
}

std::vector<double> amplitudes(double squeeze, double twist, double bump)
{
    std::vector<double> a{squeeze, twist};
    for (int k = 0; k < 8; ++k)
        a.push_back(bump * std::sin(1.0 + k));
    return a;
}

nlohmann::json set_up(const fs::path& dir)
{
    const test::MorphRun r = test::run_morph_mesh(
        {"-case", dir.string(), "-variables", "-json", (dir / "setup.json").string()});
    EXPECT_EQ(r.code, 0) << r.log;
    return nlohmann::json::parse(read_text(dir / "setup.json"));
}

class SharedDesign : public ::testing::Test
{
protected:
    static void SetUpTestSuite()
    {
        dir_ = new fs::path(
            pipe_case("shared_fit_" + std::to_string(::getpid()), shared_dict("shared")));
        setup_ = new nlohmann::json(set_up(*dir_));
    }
    static void TearDownTestSuite()
    {
        delete dir_;
        delete setup_;
    }
    static fs::path* dir_;
    static nlohmann::json* setup_;
};
fs::path* SharedDesign::dir_ = nullptr;
nlohmann::json* SharedDesign::setup_ = nullptr;

TEST_F(SharedDesign, the_set_up_stores_prescriptions_only_and_says_so)
{
    const nlohmann::json& j = *setup_;
    EXPECT_EQ(j["storage"], "shared");
    EXPECT_EQ(j["storageReason"], "designBasis shared");
    ASSERT_EQ(j["variables"].size(), 10u);
    // No field: the labels and prescriptions of 10 variables on the pipe's 779 constrained
    // points are at most 10 x 779 x 32 bytes, and 10 fields alone 10 x 24 bytes per point.
    const Points x0 = points_at(*dir_, "constant");
    EXPECT_LT(j["bytes"].get<double>(), 10 * 779 * 32 + 4096);
    EXPECT_LT(j["bytes"].get<double>(), 0.2 * 10 * 24 * double(x0.rows()));
    EXPECT_GT(j["variables"][0]["centres"].get<double>(), 0.0);
}

TEST_F(SharedDesign, a_variant_is_linear_in_its_amplitudes_and_exact_on_the_wall)
{
    const Points x0 = points_at(*dir_, "constant");
    const std::vector<double> a = amplitudes(0.5, 1.0, 0.05), b = amplitudes(-0.2, -0.5, 0.02);
    std::vector<double> sum(a.size());
    for (std::size_t k = 0; k < a.size(); ++k)
        sum[k] = a[k] + b[k];
    const Points xa = variant_points(*dir_, a), xb = variant_points(*dir_, b),
                 xs = variant_points(*dir_, sum);
    // Held choices: the same map for every prescription, linear to round-off: the solve's
    // times its condition, and the IDW correction's single-precision far terms (1e-7 of a
    // residual within the fit's tolerance). Measured 7e-10 of the displacement; variants
    // with centres of their own would differ by the tolerance itself (1e-3).
    const double largest = (xs - x0).cwiseAbs().maxCoeff();
    EXPECT_LT(((xa - x0) + (xb - x0) - (xs - x0)).cwiseAbs().maxCoeff(), 1e-8 * largest);
    EXPECT_GT((xa - x0).cwiseAbs().maxCoeff(), 0.01);
    // A squeeze alone moves the wall exactly.
    std::vector<double> squeeze(a.size(), 0.0);
    squeeze[0] = 0.5;
    expect_wall_squeezed(x0, variant_points(*dir_, squeeze), 0.5);
    EXPECT_EQ(
        (variant_points(*dir_, std::vector<double>(a.size(), 0.0)) - x0).cwiseAbs().maxCoeff(), 0.0)
        << "amplitude zero is the set-up's mesh";
}

TEST_F(SharedDesign, the_gradient_equals_central_finite_differences)
{
    const io::FoamPolyMesh foam = io::read_poly_mesh(*dir_);
    const Points w = weights(foam.mesh.points);
    write_point_field(*dir_ / "0/dJdx", w, {}, foam.mesh);
    const std::vector<double> g = gradient_from(*dir_, "0/dJdx");
    ASSERT_EQ(g.size(), 10u);
    expect_central_differences(*dir_, w, g, amplitudes(0.1, 0.5, 0.01), {0, 1, 3, 8});
}

TEST(SharedDesignSetUp, auto_takes_fields_for_few_variables_and_says_why)
{
    const fs::path dir = pipe_case("shared_auto", shared_dict("auto"));
    const nlohmann::json j = set_up(dir);
    EXPECT_EQ(j["storage"], "fields");
    EXPECT_EQ(j["storageReason"], "auto: 10 variables move (shared above 100)");
}

TEST(SharedDesignSetUp, shared_is_refused_where_the_variables_constrain_different_points)
{
    // A handle variable's handle is free in the other variables: no one fit holds for all.
    std::string dict = shared_dict("shared");
    dict.replace(dict.find("designVariables\n{"), 17,
                 "handles { core { box (-0.1 -0.1 0.9) (0.1 0.1 1.1); displacement (0 0 0); } "
                 "}\ndesignVariables\n{\n    lift { handle core; vector (0 0.1 0); }");
    const fs::path dir = pipe_case("shared_handle", dict);
    const test::MorphRun r = test::run_morph_mesh({"-case", dir.string(), "-variables"});
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_NE(r.log.find("designBasis shared is not available for the variables constrain "
                         "different points"),
              std::string::npos)
        << r.log;
    EXPECT_FALSE(fs::exists(dir / "constant/designBasis"));
    // A misspelt storage names the entry.
    const fs::path bad = pipe_case("shared_misspelt", shared_dict("share"));
    const test::MorphRun m = test::run_morph_mesh({"-case", bad.string(), "-variables"});
    EXPECT_EQ(m.code, 2) << m.log;
    EXPECT_NE(m.log.find("designBasis"), std::string::npos) << m.log;
    EXPECT_NE(m.log.find("expected 'fields'"), std::string::npos) << m.log;
}

TEST(SharedDesignSetUp, a_version_1_set_up_is_still_read)
{
    // Version 1 had fields only and no storage in its header.
    const fs::path dir = pipe_case("version_1", shared_dict("fields"));
    set_up(dir);
    std::string text = read_text(dir / "constant/designBasis");
    const std::string v2 = "meshMorph designBasis 2\n";
    ASSERT_EQ(text.rfind(v2, 0), 0u);
    text.replace(0, v2.size(), "meshMorph designBasis 1\n");
    const std::string keys = ",\"sharedTemplate\":-1,\"storage\":\"fields\"";
    const std::size_t at = text.find(keys);
    ASSERT_NE(at, std::string::npos);
    text.erase(at, keys.size());
    test::write_text(dir / "constant/designBasis", text);
    const Points x0 = points_at(dir, "constant");
    const Points x = variant_points(dir, amplitudes(0.5, 0.0, 0.0));
    EXPECT_GT((x - x0).cwiseAbs().maxCoeff(), 0.01);
}

} // namespace
} // namespace meshmorph
