// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The ranks of a run and the few collective operations the morph needs.
//!
//! Built with MPI (MESHMORPH_WITH_MPI), Communicator::world() is MPI_COMM_WORLD once a
//! ParallelSession has started MPI (the applications do so for -parallel); otherwise it is a
//! single rank and every collective is the identity. Collectives must be called by every
//! rank in the same order, as in MPI.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace meshmorph::parallel
{

class Communicator
{
public:
    //! The run's communicator (one rank until a ParallelSession starts MPI).
    static const Communicator& world();
    //! Whether this build has MPI.
    static bool available();

    int rank() const { return rank_; }
    int size() const { return size_; }
    bool master() const { return rank_ == 0; }
    bool is_parallel() const { return parallel_; }

    double max(double value) const;
    double min(double value) const;
    double sum(double value) const;
    std::int64_t sum(std::int64_t value) const;
    std::int64_t max(std::int64_t value) const;
    //! True on every rank if `value` is true on any rank.
    bool any(bool value) const;

    //! The master's bytes on every rank.
    std::string broadcast(const std::string& bytes) const;
    //! Every rank's bytes, by rank, on the master (empty elsewhere).
    std::vector<std::string> gather(const std::string& bytes) const;
    //! Bytes for each rank (given on the master, by rank) to that rank.
    std::string scatter(const std::vector<std::string>& per_rank) const;
    //! Neighbour exchange: sends[i].second to rank sends[i].first and returns, in the same
    //! order, what that rank sent here (every rank in `sends` must list this rank once). Used
    //! across processor patches; a rank may list itself (the bytes come back).
    std::vector<std::string> exchange(const std::vector<std::pair<int, std::string>>& sends) const;

    //! Trivially copyable values: gathered on the master, by rank.
    template <class T> std::vector<std::vector<T>> gather_values(const std::vector<T>& mine) const
    {
        static_assert(std::is_trivially_copyable_v<T>);
        std::vector<std::vector<T>> out;
        for (const std::string& b : gather(to_bytes(mine)))
            out.push_back(from_bytes<T>(b));
        return out;
    }
    template <class T> std::vector<T> broadcast_values(const std::vector<T>& values) const
    {
        static_assert(std::is_trivially_copyable_v<T>);
        return from_bytes<T>(broadcast(to_bytes(values)));
    }
    template <class T>
    std::vector<T> scatter_values(const std::vector<std::vector<T>>& per_rank) const
    {
        static_assert(std::is_trivially_copyable_v<T>);
        std::vector<std::string> bytes;
        for (const std::vector<T>& v : per_rank)
            bytes.push_back(to_bytes(v));
        return from_bytes<T>(scatter(bytes));
    }

private:
    friend class ParallelSession;
    Communicator() = default;
    static Communicator& mutable_world();

    template <class T> static std::string to_bytes(const std::vector<T>& v)
    {
        return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }
    template <class T> static std::vector<T> from_bytes(const std::string& b)
    {
        std::vector<T> v(b.size() / sizeof(T));
        if (!v.empty())
            std::copy(b.data(), b.data() + v.size() * sizeof(T), reinterpret_cast<char*>(v.data()));
        return v;
    }

    int rank_ = 0;
    int size_ = 1;
    bool parallel_ = false;
};

//! RAII: starts MPI for a -parallel run (MPI_Init_thread, funneled: OpenMP threads do not
//! call MPI) and finalizes it. \throw InvalidInput if this build has no MPI.
class ParallelSession
{
public:
    ParallelSession();
    ~ParallelSession();
    ParallelSession(const ParallelSession&) = delete;
    ParallelSession& operator=(const ParallelSession&) = delete;
};

} // namespace meshmorph::parallel
