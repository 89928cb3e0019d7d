// SPDX-License-Identifier: GPL-3.0-or-later
// Handle basis: B H equals a fresh fit for RBF, DM-FFD and FFD; binary round trip; broken
// files give ParseError / IoError naming the file.
#include <gtest/gtest.h>

#include <fstream>

#include "deform_test_helpers.h"
#include "helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/handle_basis.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph
{

TEST(HandleBasis, product_equals_a_fresh_fit_for_every_method)
{
    const Points h = test::random_points(60, 0.1, 0.9, 2);
    const Points x = test::random_points(500, 0.0, 1.0, 3);
    const Points H = test::smooth_field(h * 1.3) * 3.0;
    {
        RbfDeformation rbf;
        rbf.fit(h, test::smooth_field(h));
        const HandleBasis B = HandleBasis::compute(rbf, x);
        EXPECT_EQ(B.rows(), 500);
        EXPECT_EQ(B.cols(), 60);
        RbfDeformation fresh;
        fresh.fit(h, H);
        EXPECT_LE((B.apply(H) - displacements(fresh, x)).cwiseAbs().maxCoeff(), 1e-11);
    }
    {
        DmffdSettings s;
        s.lattice.control_points = {6, 6, 6};
        s.lattice.box = FfdBox{};
        DmffdDeformation dm(s);
        dm.fit(h, test::smooth_field(h));
        const HandleBasis B = HandleBasis::compute(dm, x);
        DmffdDeformation fresh(s);
        fresh.fit(h, H);
        EXPECT_LE((B.apply(H) - displacements(fresh, x)).cwiseAbs().maxCoeff(), 1e-12);
    }
    {
        const FfdLattice lattice(FfdBox{}, {4, 5, 6});
        FfdDeformation ffd(lattice);
        const Points C = test::smooth_field(lattice.control_points());
        ffd.set_control_displacements(C);
        const HandleBasis B = HandleBasis::compute(ffd, x);
        EXPECT_LE((B.apply(C) - displacements(ffd, x)).cwiseAbs().maxCoeff(), 1e-14);
    }
}

TEST(HandleBasis, greedy_basis_reproduces_the_greedy_deformation)
{
    const Points c = test::sphere_points(800, Vector3(0.5, 0.5, 0.5), 0.4);
    const Points d = test::smooth_field(c);
    const Points x = test::random_points(300, 0.0, 1.0, 5);
    GreedySettings s;
    s.tolerance = 1e-2;
    s.rms_tolerance = 1e-3;
    GreedyRbfDeformation greedy(s);
    greedy.fit(c, d);
    const HandleBasis B = HandleBasis::compute(greedy, x);
    EXPECT_EQ(B.cols(), 800);
    EXPECT_EQ(B.method(), BasisMethod::greedy_rbf);
    EXPECT_LE((B.apply(d) - displacements(greedy, x)).cwiseAbs().maxCoeff(), 1e-11);
    // Only centre columns are nonzero.
    Eigen::Index nonzero = 0;
    for (Eigen::Index j = 0; j < B.cols(); ++j)
        nonzero += B.matrix().col(j).cwiseAbs().maxCoeff() > 0.0;
    EXPECT_EQ(nonzero, greedy.report().num_centres);
}

TEST(HandleBasis, save_load_round_trip_is_bit_identical)
{
    const HandleBasis B(Eigen::MatrixXd::Random(37, 11), BasisMethod::dmffd);
    const std::string path = (test::scratch_dir("handle_basis_round_trip") / "B.bin").string();
    B.save(path);
    const HandleBasis C = HandleBasis::load(path);
    EXPECT_EQ(C.method(), BasisMethod::dmffd);
    EXPECT_TRUE((B.matrix().array() == C.matrix().array()).all());
    EXPECT_THROW(B.apply(Points::Zero(10, 3)), InvalidInput);
}

TEST(HandleBasis, broken_files_give_clear_errors)
{
    const std::filesystem::path dir = test::scratch_dir("handle_basis_broken");
    const std::string good = (dir / "good.bin").string();
    HandleBasis(Eigen::MatrixXd::Random(5, 4), BasisMethod::rbf).save(good);
    std::string bytes;
    {
        std::ifstream in(good, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    const auto write = [&](const std::string& name, const std::string& content)
    {
        const std::string p = (dir / name).string();
        std::ofstream(p, std::ios::binary) << content;
        return p;
    };
    const auto expect_parse_error = [](const std::string& path, const std::string& words)
    {
        try
        {
            HandleBasis::load(path);
            ADD_FAILURE() << path << " accepted";
        }
        catch (const ParseError& e)
        {
            EXPECT_EQ(e.path(), path);
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    std::string bad_magic = bytes;
    bad_magic[0] = 'X';
    expect_parse_error(write("magic.bin", bad_magic), "bad magic");
    std::string bad_version = bytes;
    bad_version[8] = 9;
    expect_parse_error(write("version.bin", bad_version), "version");
    expect_parse_error(write("truncated.bin", bytes.substr(0, bytes.size() - 8)), "truncated");
    expect_parse_error(write("header.bin", bytes.substr(0, 12)), "truncated");
    expect_parse_error(write("trailing.bin", bytes + "xx"), "trailing");
    EXPECT_THROW(HandleBasis::load((dir / "missing.bin").string()), IoError);
}

TEST(DmffdDeformation, lattice_refinement_reaches_the_tolerance)
{
    // A field a 4^3 lattice cannot represent; it varies along x only, so control planes are
    // inserted across x only (the paper's axis restriction).
    const Points h = test::random_points(1500, 0.0, 1.0, 12);
    Points d(h.rows(), 3);
    for (Eigen::Index i = 0; i < h.rows(); ++i)
        d.row(i) = Eigen::RowVector3d(0.05 * std::sin(6.0 * h(i, 0)), 0.0, 0.0);
    DmffdSettings s;
    s.lattice.control_points = {4, 4, 4};
    s.clamping = 1e-6;
    DmffdRefinement r;
    r.tolerance = 2e-2;
    r.max_control_points = 5000;
    r.axes = {true, false, false};
    DmffdDeformation dm(s);
    dm.fit_refined(h, d, r);
    EXPECT_GT(dm.report().iterations, 0);
    EXPECT_LE(dm.report().max_residual, 2e-2 * dm.report().max_displacement);
    EXPECT_TRUE(dm.refinement_converged());
    EXPECT_GT(dm.ffd().lattice().counts()[0], 4);
    EXPECT_EQ(dm.ffd().lattice().counts()[1], 4);
    EXPECT_EQ(dm.ffd().lattice().counts()[2], 4);
}

} // namespace meshmorph
