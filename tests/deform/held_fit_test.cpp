// SPDX-License-Identifier: GPL-3.0-or-later
// Refits with a fit's choices held (SpaceDeformation::refit, deform/held_fit.h): the same
// data give the fit's own field bit for bit, new data a field that is exact at the handles
// and linear in the data, and the transpose is that linear map's; HeldFits keeps one fit
// per set of handles and refuses new handles once frozen.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/corrected_deformation.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/held_fit.h"
#include "meshmorph/deform/idw_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph
{
namespace
{

//! A coarse greedy RBF with its IDW correction: the choices a refit holds are its centres,
//! and the correction has a real residual to take up.
std::unique_ptr<SpaceDeformation> corrected_greedy()
{
    GreedySettings coarse;
    coarse.tolerance = 0.05;
    coarse.rms_tolerance = 0.05;
    return std::make_unique<CorrectedDeformation>(std::make_unique<GreedyRbfDeformation>(coarse));
}

//! Another smooth field on the same handles, not a multiple of the first.
Points other_field(const Points& h)
{
    Points d(h.rows(), 3);
    for (Eigen::Index i = 0; i < h.rows(); ++i)
        d.row(i) << std::cos(3 * h(i, 1)), 0.2 * h(i, 0) * h(i, 2), std::sin(2 * h(i, 0)) - h(i, 1);
    return 0.05 * d;
}

struct Sphere
{
    Points h = test::sphere_points(1500, Vector3(0.5, 0.5, 0.5), 0.4);
    Points x = test::random_points(2000, 0.0, 1.0, 5);
};

} // namespace

TEST(HeldFit, a_refit_to_the_fitted_data_gives_the_fit_s_field_bit_for_bit)
{
    const Sphere s;
    const Points d = test::smooth_field(s.h);
    using Maker = std::unique_ptr<SpaceDeformation> (*)();
    const Maker plain_greedy = []
    { return std::unique_ptr<SpaceDeformation>(std::make_unique<GreedyRbfDeformation>()); };
    for (const Maker make : {Maker(corrected_greedy), plain_greedy})
    {
        const std::unique_ptr<SpaceDeformation> f = make();
        f->fit(s.h, d);
        const Points fitted = displacements(*f, s.x);
        f->refit(other_field(s.h));
        f->refit(d);
        EXPECT_EQ((displacements(*f, s.x) - fitted).cwiseAbs().maxCoeff(), 0.0)
            << f->report().method;
    }
}

TEST(HeldFit, a_refit_is_exact_at_the_handles_and_linear_in_its_data)
{
    const Sphere s;
    const std::unique_ptr<SpaceDeformation> f = corrected_greedy();
    const Points a = test::smooth_field(s.h), b = other_field(s.h);
    f->fit(s.h, a);
    ASSERT_GT(f->report().max_residual, 1e-4) << "the premise: the correction has work";
    double correction = 0.0; // the largest residual the IDW correction takes up
    const auto field = [&](const Points& data)
    {
        f->refit(data);
        correction = std::max(correction, f->report().max_residual);
        return displacements(*f, s.x);
    };
    const Points fa = field(a), fb = field(b), fsum = field(2.0 * a - b);
    // The global part is linear to round-off times its condition; the correction sums its
    // far terms in single precision (idw_tree.h), so it is linear to ~1e-7 of the residual
    // it corrects: far below the fit's tolerance (5e-2), and 1e-6 of it is the bound.
    EXPECT_LT((2.0 * fa - fb - fsum).cwiseAbs().maxCoeff(), 1e-6 * correction);
    f->refit(b);
    EXPECT_LT((displacements(*f, s.h) - b).cwiseAbs().maxCoeff(), 1e-12 * b.cwiseAbs().maxCoeff())
        << "the correction keeps the handles exact";
}

TEST(HeldFit, the_transpose_is_that_of_the_refitted_map)
{
    // <d(x), G> = <H, A> for the refitted data H, without fitting H from scratch.
    const Sphere s;
    const std::unique_ptr<SpaceDeformation> f = corrected_greedy();
    f->fit(s.h, test::smooth_field(s.h));
    const Points h = other_field(s.h);
    f->refit(h);
    const Points g = test::smooth_field(s.x);
    const Points y = displacements(*f, s.x);
    const double lhs = (y.array() * g.array()).sum();
    const double rhs = (h.array() * f->transpose(s.x, g).array()).sum();
    EXPECT_NEAR(lhs, rhs, 1e-9 * (y.array().abs() * g.array().abs()).sum());
}

TEST(HeldFit, held_fits_keep_one_fit_per_set_of_handles_and_refuse_new_ones_when_frozen)
{
    const Sphere s;
    int made = 0;
    HeldFits held(
        [&]
        {
            ++made;
            return corrected_greedy();
        });
    const Points first = s.h.topRows(1000), second = s.h;
    const std::unique_ptr<SpaceDeformation> a = held.view(), b = held.view();
    a->fit(first, test::smooth_field(first));
    b->fit(second, test::smooth_field(second));
    EXPECT_EQ(held.size(), 2u);
    held.freeze();
    // Both refit: no new deformation is made, and each view evaluates its own set's fit.
    a->fit(first, other_field(first));
    b->fit(second, other_field(second));
    EXPECT_EQ(made, 2);
    EXPECT_LT((displacements(*a, first) - other_field(first)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((displacements(*b, second) - other_field(second)).cwiseAbs().maxCoeff(), 1e-12);
    const Points moved = first.array() + 1e-3;
    EXPECT_THROW(a->fit(moved, test::smooth_field(moved)), InvalidInput);
    Points out(s.x.rows(), 3);
    EXPECT_THROW(held.view()->evaluate(s.x, out), InvalidInput) << "a view before its fit";
}

TEST(HeldFit, methods_without_choices_refit_too_and_a_refit_before_the_fit_is_refused)
{
    const Sphere s;
    IdwDeformation idw;
    EXPECT_THROW(idw.refit(s.h), InvalidInput);
    idw.fit(s.h, test::smooth_field(s.h));
    idw.refit(other_field(s.h));
    EXPECT_LT((displacements(idw, s.h) - other_field(s.h)).cwiseAbs().maxCoeff(), 1e-12);
    GreedyRbfDeformation greedy;
    EXPECT_THROW(greedy.refit(s.h), InvalidInput);
    greedy.fit(s.h, test::smooth_field(s.h));
    EXPECT_THROW(greedy.refit(s.h.topRows(10)), InvalidInput) << "another handle count";
}

} // namespace meshmorph
