// SPDX-License-Identifier: GPL-3.0-or-later
// The collectives of src/meshmorph/parallel/communicator.*: run as one rank (plain test) and
// on several ranks under mpirun (parallel_mpi_tests, main below starts MPI).
#include "meshmorph/parallel/communicator.h"

#include "meshmorph/core/exceptions.h"
#include "meshmorph/parallel/collective.h"

#include <memory>
#include <numeric>

#include <gtest/gtest.h>

namespace meshmorph::parallel
{
namespace
{

const Communicator& comm()
{
    return Communicator::world();
}

TEST(Communicator, reductions_combine_every_rank)
{
    const int n = comm().size();
    const int r = comm().rank();
    EXPECT_EQ(comm().sum(std::int64_t(r + 1)), std::int64_t(n) * (n + 1) / 2);
    EXPECT_EQ(comm().max(double(r)), double(n - 1));
    EXPECT_EQ(comm().min(double(r) + 0.5), 0.5);
    EXPECT_DOUBLE_EQ(comm().sum(0.25), 0.25 * n);
    EXPECT_EQ(comm().any(r == n - 1), true);
    EXPECT_EQ(comm().any(false), false);
}

TEST(Communicator, gather_broadcast_and_scatter_move_bytes_by_rank)
{
    const int n = comm().size();
    const int r = comm().rank();
    // Rank r sends r+1 values r*10, r*10+1, ... (rank 0 also sends a 0-byte-free payload).
    std::vector<double> mine(static_cast<std::size_t>(r + 1));
    std::iota(mine.begin(), mine.end(), 10.0 * r);
    const std::vector<std::vector<double>> all = comm().gather_values(mine);
    if (comm().master())
    {
        ASSERT_EQ(all.size(), static_cast<std::size_t>(n));
        for (int k = 0; k < n; ++k)
        {
            ASSERT_EQ(all[std::size_t(k)].size(), std::size_t(k + 1));
            EXPECT_EQ(all[std::size_t(k)].back(), 10.0 * k + k);
        }
    }
    else
        EXPECT_TRUE(all.empty());

    const std::vector<int> from_master =
        comm().broadcast_values(comm().master() ? std::vector<int>{7, 8, 9} : std::vector<int>{});
    EXPECT_EQ(from_master, (std::vector<int>{7, 8, 9}));

    std::vector<std::vector<int>> parts;
    if (comm().master())
        for (int k = 0; k < n; ++k)
            parts.push_back(std::vector<int>(std::size_t(k), k));
    EXPECT_EQ(comm().scatter_values(parts), std::vector<int>(std::size_t(r), r));
}

TEST(Communicator, exchange_swaps_bytes_with_each_listed_rank)
{
    // Every rank sends "r>k" to every rank k (itself included) and gets "k>r" back from each.
    const int n = comm().size();
    const int r = comm().rank();
    std::vector<std::pair<int, std::string>> sends;
    for (int k = 0; k < n; ++k)
        sends.emplace_back(k, std::to_string(r) + ">" + std::to_string(k) +
                                  std::string(std::size_t(k), 'x'));
    const std::vector<std::string> received = comm().exchange(sends);
    ASSERT_EQ(received.size(), std::size_t(n));
    for (int k = 0; k < n; ++k)
        EXPECT_EQ(received[std::size_t(k)],
                  std::to_string(k) + ">" + std::to_string(r) + std::string(std::size_t(r), 'x'));
}

TEST(Collective, an_error_on_one_rank_is_thrown_on_every_rank)
{
    const int last = comm().size() - 1;
    try
    {
        collective(comm(),
                   [&]
                   {
                       if (comm().rank() == last)
                           throw IoError("disk full");
                   });
        FAIL() << "no error";
    }
    catch (const IoError& e)
    {
        const std::string expected = comm().rank() == last || !comm().is_parallel()
                                         ? "disk full"
                                         : "processor" + std::to_string(last) + ": disk full";
        EXPECT_EQ(std::string(e.what()), expected);
    }
    // Nothing thrown anywhere: nothing thrown.
    EXPECT_NO_THROW(collective(comm(), [] {}));
    // on_master: the master's error on every rank, with its type.
    EXPECT_THROW(on_master(comm(), [] { throw SolverError("singular"); }), SolverError);
}

TEST(Communicator, is_parallel_only_in_a_parallel_session)
{
    EXPECT_EQ(comm().is_parallel(), comm().size() > 1 || MPI_TEST_SESSION);
}

} // namespace
} // namespace meshmorph::parallel

#if MPI_TEST_SESSION
int main(int argc, char** argv)
{
    ::testing::InitGoogleTest(&argc, argv);
    meshmorph::parallel::ParallelSession session;
    // Only the master reports, as OpenFOAM's applications do; every rank's result counts.
    if (!meshmorph::parallel::Communicator::world().master())
        delete ::testing::UnitTest::GetInstance()->listeners().Release(
            ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
    const int failed = RUN_ALL_TESTS();
    return static_cast<int>(meshmorph::parallel::Communicator::world().any(failed != 0));
}
#endif
