// SPDX-License-Identifier: GPL-3.0-or-later
// Properties of RbfDeformation: exact interpolation, affine reproduction, scale invariance,
// degenerate (2D) handle sets, duplicates, bad input, thread-count independence.
#include <gtest/gtest.h>

#include <omp.h>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph
{
namespace
{

RbfSettings settings_for(RbfKernel kernel)
{
    RbfSettings s;
    s.kernel = kernel;
    s.shape_parameter = 2.0;
    s.support_radius = 0.8;
    if (kernel == RbfKernel::polyharmonic)
        s.polyharmonic_order = 4; // r^5 with a quadratic polynomial
    return s;
}

const RbfKernel all_kernels[] = {RbfKernel::triharmonic,  RbfKernel::biharmonic,
                                 RbfKernel::polyharmonic, RbfKernel::gaussian,
                                 RbfKernel::multiquadric, RbfKernel::inverse_multiquadric,
                                 RbfKernel::wendland_c2};

Eigen::Matrix3d test_linear_map()
{
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.3, Vector3(1, 2, 3).normalized()).matrix();
    return rot * Vector3(1.2, 0.7, 1.05).asDiagonal();
}

} // namespace

TEST(RbfDeformation, interpolates_handles_for_every_kernel)
{
    const Points h = test::random_points(150);
    const Points d = test::smooth_field(h);
    const double tol = 1e-10 * test::max_norm(d);
    for (RbfKernel k : all_kernels)
    {
        RbfDeformation rbf(settings_for(k));
        rbf.fit(h, d);
        const Points got = displacements(rbf, h);
        EXPECT_LE((got - d).rowwise().norm().maxCoeff(), tol) << to_string(k);
        EXPECT_LE(rbf.report().max_residual, tol) << to_string(k);
        EXPECT_EQ(rbf.report().num_centres, 150);
        EXPECT_GT(rbf.report().condition_estimate, 1.0) << to_string(k);
    }
}

TEST(RbfDeformation, keeps_its_values_at_the_handles_with_the_bits_of_an_evaluation)
{
    const Points x = test::random_points(300);
    RbfDeformation rbf;
    EXPECT_EQ(rbf.values_at_handles(), nullptr); // not fitted yet
    rbf.fit(x, test::smooth_field(x));
    ASSERT_NE(rbf.values_at_handles(), nullptr);
    EXPECT_TRUE(rbf.values_at_handles()->cwiseEqual(displacements(rbf, x)).all());
    // A refit (same handles, new displacements) keeps the new field's values.
    rbf.refit(2.0 * test::smooth_field(x));
    EXPECT_TRUE(rbf.values_at_handles()->cwiseEqual(displacements(rbf, x)).all());
}

TEST(RbfDeformation, interpolates_without_polynomial_for_definite_kernels)
{
    const Points h = test::random_points(80);
    const Points d = test::smooth_field(h);
    for (RbfKernel k :
         {RbfKernel::gaussian, RbfKernel::inverse_multiquadric, RbfKernel::wendland_c2})
    {
        RbfSettings s = settings_for(k);
        s.polynomial = false;
        RbfDeformation rbf(s);
        rbf.fit(h, d);
        EXPECT_LE(rbf.report().max_residual, 1e-10 * test::max_norm(d)) << to_string(k);
        EXPECT_EQ(rbf.report().polynomial_terms, 0);
    }
}

TEST(RbfDeformation, reproduces_affine_motions_everywhere)
{
    const Points h = test::random_points(60);
    const Points x = test::random_points(500, -0.5, 1.5, 11); // also outside the handle hull
    const Vector3 t(0.1, -0.2, 0.05);
    const Eigen::Matrix3d maps[] = {Eigen::Matrix3d::Identity(), test_linear_map(),
                                    Vector3(1.5, 0.8, 1.1).asDiagonal().toDenseMatrix()};
    for (RbfKernel k : all_kernels)
        for (const Eigen::Matrix3d& L : maps)
        {
            RbfDeformation rbf(settings_for(k));
            rbf.fit(h, test::affine_displacements(h, L, t));
            const Points expected = test::affine_displacements(x, L, t);
            EXPECT_LE((displacements(rbf, x) - expected).cwiseAbs().maxCoeff(), 1e-9)
                << to_string(k);
        }
}

TEST(RbfDeformation, zero_displacement_is_identity)
{
    const Points h = test::random_points(40);
    RbfDeformation rbf;
    rbf.fit(h, Points::Zero(40, 3));
    const Points x = test::random_points(100, -1, 2, 3);
    EXPECT_EQ(apply(rbf, x), x);
}

TEST(RbfDeformation, invariant_under_scaling_of_the_problem)
{
    const Points h = test::random_points(100);
    const Points d = test::smooth_field(h);
    const Points x = test::random_points(200, 0, 1, 5);
    RbfDeformation ref;
    ref.fit(h, d);
    const Points expected = displacements(ref, x);
    for (double s : {1e-6, 1e6})
    {
        RbfDeformation rbf;
        const Points hs = h * s, ds = d * s;
        rbf.fit(hs, ds);
        EXPECT_LE(rbf.report().max_residual, 1e-10 * s * test::max_norm(d));
        const Points got = displacements(rbf, x * s) / s;
        EXPECT_LE((got - expected).cwiseAbs().maxCoeff(), 1e-9 * test::max_norm(d)) << s;
    }
}

TEST(RbfDeformation, coplanar_handles_reproduce_in_plane_affine_motion)
{
    // Handles on a tilted plane: P = [1 x y z] is rank 3; the degenerate term is dropped.
    Points h = test::random_points(80);
    const Vector3 n = Vector3(0.2, -0.3, 1.0).normalized();
    for (Eigen::Index i = 0; i < h.rows(); ++i)
        h.row(i) -= (n.dot(h.row(i).transpose()) - 0.4) * n.transpose();
    // In-plane affine motion: rotation about the normal, scaling, translation in the plane.
    const Eigen::Matrix3d L = Eigen::AngleAxisd(0.4, n).matrix() * 1.1;
    const Vector3 t = Vector3(0.1, 0.2, 0.0) - n.dot(Vector3(0.1, 0.2, 0.0)) * n;
    const Points d = test::affine_displacements(h, L, t);
    for (RbfKernel k : {RbfKernel::triharmonic, RbfKernel::biharmonic, RbfKernel::multiquadric,
                        RbfKernel::polyharmonic})
    {
        RbfDeformation rbf(settings_for(k));
        rbf.fit(h, d);
        EXPECT_EQ(rbf.report().polynomial_terms, k == RbfKernel::polyharmonic ? 6 : 3);
        EXPECT_LE(rbf.report().max_residual, 1e-10 * test::max_norm(d)) << to_string(k);
        // Other points of the plane follow the affine motion exactly.
        Points x = test::random_points(100, -0.5, 1.5, 9);
        for (Eigen::Index i = 0; i < x.rows(); ++i)
            x.row(i) -= (n.dot(x.row(i).transpose()) - 0.4) * n.transpose();
        EXPECT_LE(
            (displacements(rbf, x) - test::affine_displacements(x, L, t)).cwiseAbs().maxCoeff(),
            1e-9)
            << to_string(k);
    }
}

TEST(RbfDeformation, collinear_and_tiny_handle_sets_work)
{
    Points line(5, 3);
    for (int i = 0; i < 5; ++i)
        line.row(i) = Eigen::RowVector3d(i, 2.0 * i, -i) * 0.1;
    const Points d =
        test::affine_displacements(line, Eigen::Matrix3d::Identity() * 1.2, Vector3(0, 0.1, 0));
    RbfDeformation rbf;
    rbf.fit(line, d);
    EXPECT_EQ(rbf.report().polynomial_terms, 2);
    EXPECT_LE(rbf.report().max_residual, 1e-12);

    RbfDeformation one;
    one.fit(Points::Constant(1, 3, 0.5), Points::Constant(1, 3, 0.25));
    const Points x = test::random_points(10);
    EXPECT_LE((displacements(one, x).array() - 0.25).abs().maxCoeff(), 1e-15);
}

TEST(RbfDeformation, merges_duplicates_and_rejects_conflicting_ones)
{
    Points h = test::random_points(20);
    Points d = test::smooth_field(h);
    Points h2(21, 3), d2(21, 3);
    h2 << h, h.row(4);
    d2 << d, d.row(4);
    RbfDeformation rbf;
    rbf.fit(h2, d2);
    EXPECT_EQ(rbf.report().num_centres, 20);
    EXPECT_EQ(rbf.report().num_merged_duplicates, 1);
    EXPECT_LE(rbf.report().max_residual, 1e-10 * test::max_norm(d));

    d2.row(20) += Eigen::RowVector3d(0.01, 0, 0);
    try
    {
        rbf.fit(h2, d2);
        FAIL() << "conflicting duplicates accepted";
    }
    catch (const InvalidInput& e)
    {
        const std::string what = e.what();
        EXPECT_NE(what.find("handles 4 "), std::string::npos) << what;
        EXPECT_NE(what.find(" and 20 "), std::string::npos) << what;
    }
}

TEST(RbfDeformation, rejects_bad_input_with_clear_errors)
{
    RbfDeformation rbf;
    const Points h = test::random_points(10);
    EXPECT_THROW(rbf.fit(Points(0, 3), Points(0, 3)), InvalidInput);
    EXPECT_THROW(rbf.fit(h, Points::Zero(9, 3)), InvalidInput);
    Points bad = h;
    bad(3, 1) = std::nan("");
    EXPECT_THROW(rbf.fit(bad, Points::Zero(10, 3)), InvalidInput);
    EXPECT_THROW(rbf.fit(h, bad), InvalidInput);
    Points out(10, 3);
    EXPECT_THROW(rbf.evaluate(h, out), InvalidInput); // not fitted

    RbfSettings s;
    s.kernel = RbfKernel::gaussian;
    s.shape_parameter = -1.0;
    EXPECT_THROW(RbfDeformation{s}, InvalidInput);
    s.kernel = RbfKernel::wendland_c2;
    s.support_radius = 0.0;
    EXPECT_THROW(RbfDeformation{s}, InvalidInput);
    s = RbfSettings{};
    s.polynomial = false;
    EXPECT_THROW(RbfDeformation{s}, InvalidInput); // r^3 needs the polynomial
    s = RbfSettings{};
    s.kernel = RbfKernel::polyharmonic;
    s.polyharmonic_order = 1;
    EXPECT_THROW(RbfDeformation{s}, InvalidInput);
    EXPECT_THROW(rbf_kernel_from_string("cubic"), InvalidInput);
    s = RbfSettings{};
    s.max_dense_centres = 5;
    RbfDeformation small(s);
    EXPECT_THROW(small.fit(h, Points::Zero(10, 3)), InvalidInput);
    EXPECT_EQ(rbf_kernel_from_string("inverse_multiquadric"), RbfKernel::inverse_multiquadric);
}

TEST(RbfDeformation, reports_solver_failure_for_singular_gaussian)
{
    // A very flat Gaussian makes the matrix numerically singular: SolverError, not garbage.
    RbfSettings s;
    s.kernel = RbfKernel::gaussian;
    s.polynomial = false;
    s.shape_parameter = 1e-4;
    RbfDeformation rbf(s);
    const Points h = test::random_points(60);
    EXPECT_THROW(rbf.fit(h, test::smooth_field(h)), SolverError);
}

TEST(RbfDeformation, evaluation_is_independent_of_thread_count)
{
    const Points h = test::random_points(300);
    RbfDeformation rbf;
    rbf.fit(h, test::smooth_field(h));
    const Points x = test::random_points(5000, -0.2, 1.2, 13);
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const Points one = displacements(rbf, x);
    omp_set_num_threads(2);
    const Points two = displacements(rbf, x);
    omp_set_num_threads(saved);
    EXPECT_TRUE((one.array() == two.array()).all());
    // Same for the compactly supported kernel (grid path).
    RbfSettings s;
    s.kernel = RbfKernel::wendland_c2;
    s.support_radius = 0.5;
    RbfDeformation w(s);
    w.fit(h, test::smooth_field(h));
    omp_set_num_threads(1);
    const Points w1 = displacements(w, x);
    omp_set_num_threads(2);
    const Points w2 = displacements(w, x);
    omp_set_num_threads(saved);
    EXPECT_TRUE((w1.array() == w2.array()).all());
}

TEST(RbfDeformation, refit_equals_fresh_fit_and_handle_basis_reproduces_it)
{
    const Points h = test::random_points(120);
    const Points x = test::random_points(300, -0.3, 1.3, 17);
    RbfDeformation rbf;
    rbf.fit(h, test::smooth_field(h));
    const Eigen::MatrixXd B = rbf.handle_basis(x);
    const Points d2 = test::smooth_field(h * 1.7) * 0.5;
    rbf.refit(d2);
    RbfDeformation fresh;
    fresh.fit(h, d2);
    const Points expected = displacements(fresh, x);
    EXPECT_LE((displacements(rbf, x) - expected).cwiseAbs().maxCoeff(), 1e-12);
    const Points bh = B * d2;
    EXPECT_LE((bh - expected).cwiseAbs().maxCoeff(), 1e-11);
}

} // namespace meshmorph

namespace meshmorph
{

TEST(RbfDeformation, matches_a_direct_solve_of_eq8)
{
    // Reference: the full (m+4) x (m+4) system of Eq. 8 solved by full-pivoting LU.
    const Points h = test::random_points(50, 0.0, 2.0, 23);
    const Points d = test::smooth_field(h);
    const Points x = test::random_points(100, -0.5, 2.5, 29);
    for (RbfKernel k : {RbfKernel::triharmonic, RbfKernel::biharmonic, RbfKernel::multiquadric,
                        RbfKernel::gaussian, RbfKernel::wendland_c2})
    {
        RbfSettings s;
        s.kernel = k;
        s.shape_parameter = 1.5;
        s.support_radius = 1.5;
        const auto phi = [&](double r)
        {
            switch (k)
            {
            case RbfKernel::triharmonic:
                return r * r * r;
            case RbfKernel::biharmonic:
                return r;
            case RbfKernel::multiquadric:
                return std::sqrt(1.0 + 2.25 * r * r);
            case RbfKernel::gaussian:
                return std::exp(-2.25 * r * r);
            default:
            {
                const double t = r / 1.5;
                return t < 1.0 ? std::pow(1.0 - t, 4) * (4.0 * t + 1.0) : 0.0;
            }
            }
        };
        const Eigen::Index m = h.rows();
        Eigen::MatrixXd M = Eigen::MatrixXd::Zero(m + 4, m + 4);
        Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m + 4, 3);
        for (Eigen::Index i = 0; i < m; ++i)
        {
            for (Eigen::Index j = 0; j < m; ++j)
                M(i, j) = phi((h.row(i) - h.row(j)).norm());
            M.block(i, m, 1, 3) = h.row(i);
            M(i, m + 3) = 1.0;
            M.block(m, i, 3, 1) = h.row(i).transpose();
            M(m + 3, i) = 1.0;
            rhs.row(i) = d.row(i);
        }
        const Eigen::MatrixXd W = M.fullPivLu().solve(rhs);
        Points expected(x.rows(), 3);
        for (Eigen::Index i = 0; i < x.rows(); ++i)
        {
            Eigen::RowVector3d v = x.row(i) * W.middleRows(m, 3) + W.row(m + 3);
            for (Eigen::Index j = 0; j < m; ++j)
                v += phi((x.row(i) - h.row(j)).norm()) * W.row(j);
            expected.row(i) = v;
        }
        RbfDeformation rbf(s);
        rbf.fit(h, d);
        EXPECT_LE((displacements(rbf, x) - expected).cwiseAbs().maxCoeff(),
                  1e-8 * test::max_norm(expected))
            << to_string(k);
    }
}

namespace
{

//! A flat Gaussian on 40 points: condition ~1e13, factorisable, with a round-off residual.
struct FlatGaussianFit
{
    RbfSettings settings;
    Points h = test::random_points(40);
    Points d = test::smooth_field(h);
    double relative_residual = 0.0; //!< of the fit with `settings` as constructed
    FlatGaussianFit()
    {
        settings.kernel = RbfKernel::gaussian;
        settings.shape_parameter = 1.0;
        settings.condition_warning = 1e6;
        RbfDeformation rbf(settings);
        rbf.fit(h, d);
        relative_residual = rbf.report().max_residual / rbf.report().max_displacement;
    }
};

} // namespace

TEST(RbfDeformation, warns_when_a_large_condition_number_shows_in_the_residual)
{
    FlatGaussianFit f;
    ASSERT_GT(f.relative_residual, 0.0) << "the premise: round-off leaves a residual";
    for (const double factor : {0.5, 2.0})
    {
        f.settings.residual_warning = factor * f.relative_residual;
        RbfDeformation rbf(f.settings);
        const log::CaptureScope capture;
        rbf.fit(f.h, f.d);
        EXPECT_GT(rbf.report().condition_estimate, f.settings.condition_warning);
        const bool warned =
            capture.text().find("Warning: RBF (gaussian): condition estimate") != std::string::npos;
        EXPECT_EQ(warned, factor < 1.0) << "residual threshold " << factor << " x the residual\n"
                                        << capture.text();
        if (warned)
        {
            EXPECT_NE(capture.text().find("rbf { greedy { } }"), std::string::npos)
                << "the warning names the key that helps";
        }
    }
}

TEST(RbfDeformation, ill_conditioning_that_shows_is_a_solver_error_when_asked)
{
    FlatGaussianFit f;
    ASSERT_GT(f.relative_residual, 0.0) << "the premise: round-off leaves a residual";
    f.settings.residual_warning = 0.5 * f.relative_residual;
    f.settings.ill_conditioning_is_error = true;
    RbfDeformation rbf(f.settings);
    const log::CaptureScope capture;
    try
    {
        rbf.fit(f.h, f.d);
        ADD_FAILURE() << "no SolverError";
    }
    catch (const SolverError& e)
    {
        EXPECT_NE(std::string(e.what()).find("condition estimate"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(rbf.is_fitted());
    EXPECT_EQ(capture.text().find("Warning"), std::string::npos) << capture.text();
}

TEST(RbfDeformation, a_large_condition_number_fitted_to_round_off_does_not_warn)
{
    // The condition estimate is above the default warning threshold, and iterative
    // refinement fits the handles to ~1e-8 of the largest displacement, within the default
    // residual_warning of 1e-6.
    const test::ClusteredHandles c;
    const RbfSettings defaults;
    RbfDeformation rbf;
    const log::CaptureScope capture;
    rbf.fit(c.h, c.d);
    const FitReport& r = rbf.report();
    ASSERT_GT(r.condition_estimate, defaults.condition_warning) << "the premise";
    ASSERT_LT(r.max_residual, defaults.residual_warning * r.max_displacement) << "the premise";
    EXPECT_EQ(capture.text().find("Warning"), std::string::npos) << capture.text();
}

TEST(RbfDeformation, iterative_refinement_never_increases_the_residual)
{
    // Handles clustered in a small region of a large domain (like the cells near a body in a
    // snappyHexMesh case) give a condition number ~5e12. Refinement cannot go below the
    // round-off of evaluating the expansion itself (eps * sum |w_j phi_j|, large when the
    // weights are), so this checks it never hurts and keeps the residual ~1e-8 relative.
    const test::ClusteredHandles c;
    const Points& h = c.h;
    const Points& d = c.d;
    RbfSettings s;
    s.refinement_steps = 0;
    s.condition_warning = 1e14;
    RbfDeformation plain(s);
    plain.fit(h, d);
    s.refinement_steps = 3;
    RbfDeformation refined(s);
    refined.fit(h, d);
    EXPECT_GT(refined.report().condition_estimate, 1e11);
    EXPECT_LE(refined.report().max_residual, plain.report().max_residual);
    EXPECT_LE(refined.report().max_residual, 1e-8 * test::max_norm(d));
}

} // namespace meshmorph

namespace meshmorph
{
TEST(RbfDeformation, fit_is_independent_of_thread_count)
{
    const Points h = test::random_points(1500, 0.0, 1.0, 37);
    const Points d = test::smooth_field(h);
    const Points x = test::random_points(300, 0.0, 1.0, 39);
    const int saved = omp_get_max_threads();
    Points result[2];
    for (int t = 1; t <= 2; ++t)
    {
        omp_set_num_threads(t);
        RbfDeformation rbf;
        rbf.fit(h, d);
        result[t - 1] = displacements(rbf, x);
    }
    omp_set_num_threads(saved);
    EXPECT_TRUE((result[0].array() == result[1].array()).all())
        << (result[0] - result[1]).cwiseAbs().maxCoeff();
}
} // namespace meshmorph
