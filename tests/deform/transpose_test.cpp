// SPDX-License-Identifier: GPL-3.0-or-later
// The reverse pass of a sensitivity (SpaceDeformation::transpose): for weights G at the
// points, the adjoint A of the prescribed displacements H with <d(x), G> = <H, A> to first
// order. Checked three ways: against the explicit handle basis (B^T G), by the inner-product
// identity of a linear map, and against central finite differences where the map is not
// linear (the limit).
#include <gtest/gtest.h>

#include <random>
#include <tuple>

#include <omp.h>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/corrected_deformation.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/idw_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph
{
namespace
{

Points random_weights(Eigen::Index n, unsigned seed)
{
    std::mt19937 gen(seed);
    std::normal_distribution<double> normal;
    Points g(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
            g(i, k) = normal(gen);
    return g;
}

double inner(const Points& a, const Points& b)
{
    return (a.array() * b.array()).sum();
}

//! The scale an inner product's round-off is measured against: sum |a_i| |b_i|.
double magnitude(const Points& a, const Points& b)
{
    return (a.array().abs() * b.array().abs()).sum();
}

//! Query points: random ones in the box around the handles, and some handles themselves
//! (a morph evaluates its field at every constraint).
Points queries(const Points& handles, Eigen::Index n)
{
    Points x(n + 50, 3);
    x.topRows(n) = test::random_points(n, -0.2, 1.2, 11);
    x.bottomRows(50) = handles.topRows(50);
    return x;
}

} // namespace

TEST(Transpose, of_the_greedy_rbf_is_the_handle_basis_transposed)
{
    const Points h = test::sphere_points(400, Vector3(0.5, 0.5, 0.5), 0.4);
    GreedyRbfDeformation greedy;
    greedy.fit(h, test::smooth_field(h));
    ASSERT_LT(Index(greedy.centre_indices().size()), h.rows()); // some constraints not centres
    const Points x = queries(h, 300);
    const Points g = random_weights(x.rows(), 3);
    const Points a = greedy.transpose(x, g);
    const Points expected = greedy.handle_basis(x).transpose() * g;
    // The same sums in another order: round-off of the sums' magnitude.
    EXPECT_LT((a - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
}

TEST(Transpose, of_the_direct_rbf_is_the_handle_basis_transposed)
{
    const Points h = test::sphere_points(300, Vector3(0.5, 0.5, 0.5), 0.4);
    RbfDeformation rbf;
    rbf.fit(h, test::smooth_field(h));
    const Points x = queries(h, 300);
    const Points g = random_weights(x.rows(), 4);
    const Points a = rbf.transpose(x, g);
    const Points expected = rbf.handle_basis(x).transpose() * g;
    // Both sides carry the direct solve's round-off: eps times its condition number.
    const double tolerance = 1e-15 * rbf.report().condition_estimate;
    ASSERT_LT(tolerance, 1e-6);
    EXPECT_LT((a - expected).cwiseAbs().maxCoeff(), tolerance * expected.cwiseAbs().maxCoeff())
        << "condition estimate " << rbf.report().condition_estimate;
}

TEST(Transpose, of_the_idw_sum_holds_the_inner_product_identity)
{
    const Points h = test::sphere_points(3000, Vector3(0.5, 0.5, 0.5), 0.4);
    const Points x = queries(h, 4000);
    const Points g = random_weights(x.rows(), 5);
    const Points v = test::residual_like_field(h, 0.15);
    // theta 0: double-precision direct sums, agreement to round-off; the tree (with quiet
    // nodes): single-precision forward sums (~1e-7 per term) against the double transpose;
    // exponents (2, 4): the tree's double-precision kernels of any weight.
    for (const auto& [theta, far, near] : {std::tuple{0.0, 3, 5}, {0.2, 3, 5}, {0.2, 2, 4}})
    {
        IdwSettings settings;
        settings.theta = theta;
        settings.far_exponent = far;
        settings.near_exponent = near;
        IdwDeformation idw(settings);
        idw.fit(h, v, test::small_values(v));
        const Points a = idw.transpose(x, g);
        const Points y = displacements(idw, x);
        const bool single = theta > 0.0 && far == 3 && near == 5;
        const double tolerance = single ? 1e-6 : 1e-12;
        EXPECT_NEAR(inner(y, g), inner(v, a), tolerance * magnitude(y, g)) << "theta " << theta;
        // Another set of values through the same tree: the transpose is of the values.
        const Points w = test::smooth_field(h);
        idw.fit(h, w, test::small_values(v));
        EXPECT_NEAR(inner(displacements(idw, x), g), inner(w, a),
                    tolerance * magnitude(displacements(idw, x), g))
            << "theta " << theta;
    }
}

TEST(Transpose, of_a_corrected_greedy_fit_holds_the_inner_product_identity)
{
    // A coarse global fit leaves a real residual to the correction (tree, default theta).
    const Points h = test::sphere_points(2000, Vector3(0.5, 0.5, 0.5), 0.4);
    const Points d = test::smooth_field(h);
    GreedySettings coarse;
    coarse.tolerance = 0.05;
    coarse.rms_tolerance = 0.05;
    CorrectedDeformation corrected(std::make_unique<GreedyRbfDeformation>(coarse));
    corrected.fit(h, d);
    ASSERT_GT(corrected.report().max_residual, 1e-4); // the correction has work to do
    const Points x = queries(h, 3000);
    const Points g = random_weights(x.rows(), 6);
    const Points y = displacements(corrected, x);
    EXPECT_NEAR(inner(y, g), inner(d, corrected.transpose(x, g)), 1e-6 * magnitude(y, g));
}

TEST(Transpose, of_a_limited_field_equals_central_finite_differences)
{
    // A translated inner sphere inside a fixed outer one: the RBF overshoots beside it, so
    // the limit is active at some points; a unique largest prescription (a slight tilt).
    const Points inner_sphere = test::sphere_points(200, Vector3(0.5, 0.5, 0.5), 0.15);
    const Points outer = test::sphere_points(300, Vector3(0.5, 0.5, 0.5), 0.5);
    Points h(inner_sphere.rows() + outer.rows(), 3);
    h << inner_sphere, outer;
    Points d = Points::Zero(h.rows(), 3);
    for (Eigen::Index i = 0; i < inner_sphere.rows(); ++i)
        d.row(i) << 0.05 + 0.01 * inner_sphere(i, 0), 0.0, 0.0;
    IdwSettings direct;
    direct.theta = 0.0; // double-precision sums, so that differences see no float noise
    CorrectedDeformation limited(std::make_unique<RbfDeformation>(), direct, true);
    limited.fit(h, d);
    const Points x = test::random_points(2000, 0.1, 0.9, 12);
    CorrectedDeformation unlimited(std::make_unique<RbfDeformation>(), direct, false);
    unlimited.fit(h, d);
    const Points free = displacements(unlimited, x);
    ASSERT_GT((free.rowwise().norm().array() > limited.report().max_displacement).count(), 0)
        << "the limit is not active anywhere: the test would not test it";
    const Points g = random_weights(x.rows(), 7);
    const Points a = limited.transpose(x, g);
    const Points delta = random_weights(h.rows(), 8) * 1e-3;
    const double eps = 1e-4; // the limit's kinks are far; round-off / eps ~ 1e-12
    const auto objective = [&](double t)
    {
        CorrectedDeformation moved(std::make_unique<RbfDeformation>(), direct, true);
        moved.fit(h, d + t * delta);
        return inner(displacements(moved, x), g);
    };
    const double fd = (objective(eps) - objective(-eps)) / (2.0 * eps);
    EXPECT_NEAR(fd, inner(delta, a), 1e-6 * std::abs(inner(delta, a)));
}

TEST(Transpose, gives_the_same_bits_with_one_and_two_threads)
{
    // Enough points for the IDW transpose's partial sums and the RBF's kernel pieces to be
    // spread over the threads.
    const Points h = test::sphere_points(3000, Vector3(0.5, 0.5, 0.5), 0.4);
    const Points x = queries(h, 20000);
    const Points g = random_weights(x.rows(), 9);
    GreedySettings coarse;
    coarse.tolerance = 0.02;
    coarse.rms_tolerance = 0.02;
    const int threads = omp_get_max_threads();
    std::vector<Points> adjoints;
    for (const int t : {1, 2})
    {
        omp_set_num_threads(t);
        CorrectedDeformation corrected(std::make_unique<GreedyRbfDeformation>(coarse),
                                       IdwSettings{}, true);
        corrected.fit(h, test::smooth_field(h));
        adjoints.push_back(corrected.transpose(x, g));
    }
    omp_set_num_threads(threads);
    EXPECT_EQ(adjoints[0], adjoints[1]);
}

TEST(Transpose, before_the_fit_or_with_a_weight_row_per_point_missing_is_refused)
{
    const Points h = test::sphere_points(100, Vector3(0.5, 0.5, 0.5), 0.4);
    IdwDeformation idw;
    EXPECT_THROW(idw.transpose(h, h), InvalidInput); // before fit()
    idw.fit(h, test::smooth_field(h));
    EXPECT_THROW(idw.transpose(h, h.topRows(10)), InvalidInput);
}

} // namespace meshmorph
