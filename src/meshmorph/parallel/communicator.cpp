// SPDX-License-Identifier: GPL-3.0-or-later
// MPI_COMM_WORLD behind a small interface; one rank without MPI.
#include "meshmorph/parallel/communicator.h"

#include <limits>

#include "meshmorph/core/config.h"
#include "meshmorph/core/exceptions.h"

#if MESHMORPH_WITH_MPI
#include <mpi.h>
#endif

namespace meshmorph::parallel
{

namespace
{

//! One rank: the bytes sent to itself come back; any other rank is an error.
std::vector<std::string> exchange_alone(const std::vector<std::pair<int, std::string>>& sends)
{
    std::vector<std::string> received;
    for (const auto& [peer, bytes] : sends)
    {
        if (peer != 0)
            throw InvalidInput("parallel: no rank " + std::to_string(peer) + " in a serial run");
        received.push_back(bytes);
    }
    return received;
}

#if MESHMORPH_WITH_MPI
//! MPI counts and displacements are int: a message above 2 GiB is refused, not truncated.
int checked_count(std::size_t bytes)
{
    if (bytes > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw InvalidInput("parallel: a message of " + std::to_string(bytes) +
                           " bytes exceeds MPI's 2 GiB limit");
    return static_cast<int>(bytes);
}

template <class T> T reduce(const Communicator& c, T value, MPI_Datatype type, MPI_Op op)
{
    if (!c.is_parallel())
        return value;
    T out{};
    MPI_Allreduce(&value, &out, 1, type, op, MPI_COMM_WORLD);
    return out;
}
#endif

} // namespace

Communicator& Communicator::mutable_world()
{
    static Communicator world;
    return world;
}

const Communicator& Communicator::world()
{
    return mutable_world();
}

bool Communicator::available()
{
    return MESHMORPH_WITH_MPI != 0;
}

#if MESHMORPH_WITH_MPI

double Communicator::max(double value) const
{
    return reduce(*this, value, MPI_DOUBLE, MPI_MAX);
}
double Communicator::min(double value) const
{
    return reduce(*this, value, MPI_DOUBLE, MPI_MIN);
}
double Communicator::sum(double value) const
{
    return reduce(*this, value, MPI_DOUBLE, MPI_SUM);
}
std::int64_t Communicator::sum(std::int64_t value) const
{
    return reduce(*this, value, MPI_INT64_T, MPI_SUM);
}
std::int64_t Communicator::max(std::int64_t value) const
{
    return reduce(*this, value, MPI_INT64_T, MPI_MAX);
}
bool Communicator::any(bool value) const
{
    return reduce(*this, static_cast<int>(value), MPI_INT, MPI_MAX) != 0;
}

std::string Communicator::broadcast(const std::string& bytes) const
{
    if (!parallel_)
        return bytes;
    std::int64_t size = static_cast<std::int64_t>(bytes.size());
    MPI_Bcast(&size, 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
    std::string out = master() ? bytes : std::string(static_cast<std::size_t>(size), '\0');
    MPI_Bcast(out.data(), checked_count(out.size()), MPI_CHAR, 0, MPI_COMM_WORLD);
    return out;
}

std::vector<std::string> Communicator::gather(const std::string& bytes) const
{
    if (!parallel_)
        return {bytes};
    const int mine = checked_count(bytes.size());
    std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(counts.size());
    MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::size_t total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r)
    {
        offsets[r] = checked_count(total);
        total += static_cast<std::size_t>(counts[r]);
    }
    std::string all(master() ? total : 0, '\0');
    MPI_Gatherv(bytes.data(), mine, MPI_CHAR, all.data(), counts.data(), offsets.data(), MPI_CHAR,
                0, MPI_COMM_WORLD);
    std::vector<std::string> out;
    if (master())
        for (std::size_t r = 0; r < counts.size(); ++r)
            out.push_back(all.substr(static_cast<std::size_t>(offsets[r]),
                                     static_cast<std::size_t>(counts[r])));
    return out;
}

std::string Communicator::scatter(const std::vector<std::string>& per_rank) const
{
    if (!parallel_)
        return per_rank.empty() ? std::string() : per_rank.front();
    std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(counts.size());
    std::string all;
    if (master())
        for (std::size_t r = 0; r < counts.size(); ++r)
        {
            const std::string& part = r < per_rank.size() ? per_rank[r] : std::string();
            counts[r] = checked_count(part.size());
            offsets[r] = checked_count(all.size());
            all += part;
        }
    int mine = 0;
    MPI_Scatter(counts.data(), 1, MPI_INT, &mine, 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::string out(static_cast<std::size_t>(mine), '\0');
    MPI_Scatterv(all.data(), counts.data(), offsets.data(), MPI_CHAR, out.data(), mine, MPI_CHAR, 0,
                 MPI_COMM_WORLD);
    return out;
}

std::vector<std::string>
Communicator::exchange(const std::vector<std::pair<int, std::string>>& sends) const
{
    if (!parallel_)
        return exchange_alone(sends);
    const std::size_t n = sends.size();
    // Sizes first (so that receives can be sized), then the bytes; non-blocking both ways so
    // the order in which ranks list their neighbours cannot deadlock.
    std::vector<std::int64_t> out_sizes(n), in_sizes(n);
    std::vector<MPI_Request> requests(2 * n);
    for (std::size_t i = 0; i < n; ++i)
    {
        out_sizes[i] = static_cast<std::int64_t>(sends[i].second.size());
        MPI_Irecv(&in_sizes[i], 1, MPI_INT64_T, sends[i].first, 0, MPI_COMM_WORLD, &requests[i]);
        MPI_Isend(&out_sizes[i], 1, MPI_INT64_T, sends[i].first, 0, MPI_COMM_WORLD,
                  &requests[n + i]);
    }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    std::vector<std::string> received(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        received[i].assign(static_cast<std::size_t>(in_sizes[i]), '\0');
        MPI_Irecv(received[i].data(), checked_count(received[i].size()), MPI_CHAR, sends[i].first,
                  1, MPI_COMM_WORLD, &requests[i]);
        MPI_Isend(sends[i].second.data(), checked_count(sends[i].second.size()), MPI_CHAR,
                  sends[i].first, 1, MPI_COMM_WORLD, &requests[n + i]);
    }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    return received;
}

ParallelSession::ParallelSession()
{
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    Communicator& world = Communicator::mutable_world();
    MPI_Comm_rank(MPI_COMM_WORLD, &world.rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &world.size_);
    world.parallel_ = true;
}

ParallelSession::~ParallelSession()
{
    Communicator& world = Communicator::mutable_world();
    world = Communicator();
    MPI_Finalize();
}

#else // one rank

double Communicator::max(double value) const
{
    return value;
}
double Communicator::min(double value) const
{
    return value;
}
double Communicator::sum(double value) const
{
    return value;
}
std::int64_t Communicator::sum(std::int64_t value) const
{
    return value;
}
std::int64_t Communicator::max(std::int64_t value) const
{
    return value;
}
bool Communicator::any(bool value) const
{
    return value;
}
std::string Communicator::broadcast(const std::string& bytes) const
{
    return bytes;
}
std::vector<std::string> Communicator::gather(const std::string& bytes) const
{
    return {bytes};
}
std::string Communicator::scatter(const std::vector<std::string>& per_rank) const
{
    return per_rank.empty() ? std::string() : per_rank.front();
}

std::vector<std::string>
Communicator::exchange(const std::vector<std::pair<int, std::string>>& sends) const
{
    return exchange_alone(sends);
}

ParallelSession::ParallelSession()
{
    throw InvalidInput("-parallel: this build of meshMorph has no MPI support (install "
                       "libopenmpi-dev and rebuild; CMake option MESHMORPH_WITH_MPI)");
}

ParallelSession::~ParallelSession() = default;

#endif

} // namespace meshmorph::parallel
