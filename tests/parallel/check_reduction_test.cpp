// SPDX-License-Identifier: GPL-3.0-or-later
// reduce_check_results on every rank's results: one rank (plain test) and several under
// mpirun (parallel_mpi_tests).
#include "meshmorph/quality/check_reduction.h"

#include <cmath>

#include <gtest/gtest.h>

#include "meshmorph/quality/face_orthogonality.h"

namespace meshmorph
{
namespace
{

const parallel::Communicator& comm()
{
    return parallel::Communicator::world();
}

//! Rank r's results: numbers that depend on r, a set on odd ranks only, a failure on the last.
std::vector<CheckResult> results_of_rank(int r, int n)
{
    CheckResult ortho(CheckId::face_orthogonality);
    const double cos_sum = 0.9 * (r + 1), count = r + 1;
    ortho.add("maxNonOrthogonality", 10.0 * (r + 1));
    ortho.add_average("avgNonOrthogonality", non_orthogonality_degrees(cos_sum / count), cos_sum,
                      Index(count));
    ortho.add("nonOrthogonalityErrors", Index(r));
    if (r == n - 1)
        ortho.failure = "nonOrthogonality";
    if (r % 2 == 1)
        ortho.add_set("nonOrthoFaces", MeshSet::Kind::face, {Index(r), Index(r + 1)},
                      "non-orthogonal faces");
    CheckResult volumes(CheckId::cell_volumes);
    volumes.add("minVolume", 1.0 + r);
    volumes.add("totalVolume", 2.0);
    volumes.add("boundaryOpenness", Vector3(r, 0, 0)); // computed globally: the master's
    return {ortho, volumes};
}

TEST(CheckReduction, combines_every_ranks_numbers_and_sets_on_the_master)
{
    const int n = comm().size();
    const std::vector<CheckResult> mine = results_of_rank(comm().rank(), n);
    const std::vector<CheckResult> all = reduce_check_results(mine, comm());
    if (!comm().master())
    {
        EXPECT_EQ(all[0].count("nonOrthogonalityErrors"), mine[0].count("nonOrthogonalityErrors"));
        return;
    }
    ASSERT_EQ(all.size(), 2u);
    EXPECT_EQ(all[0].real("maxNonOrthogonality"), 10.0 * n);
    EXPECT_EQ(all[0].count("nonOrthogonalityErrors"), Index(n) * (n - 1) / 2);
    // The average of the cosines, not of the angles: every rank's mean cosine is 0.9.
    EXPECT_NEAR(all[0].real("avgNonOrthogonality"), non_orthogonality_degrees(0.9), 1e-12);
    EXPECT_EQ(all[0].failure, "nonOrthogonality");
    Index odd_ranks = n / 2;
    if (odd_ranks > 0)
    {
        ASSERT_EQ(all[0].sets.size(), 1u);
        EXPECT_EQ(all[0].sets[0].size(), 2 * odd_ranks);
        EXPECT_TRUE(all[0].sets[0].set.labels.empty()); // the master has none of its own
    }
    EXPECT_EQ(all[1].real("minVolume"), 1.0);
    EXPECT_DOUBLE_EQ(all[1].real("totalVolume"), 2.0 * n);
    EXPECT_EQ(all[1].vector("boundaryOpenness").x(), 0.0);
}

} // namespace
} // namespace meshmorph
