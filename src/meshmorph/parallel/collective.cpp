// SPDX-License-Identifier: GPL-3.0-or-later
// Collective errors: the lowest failing rank's error, thrown on every rank.
#include "meshmorph/parallel/collective.h"

#include "meshmorph/core/exceptions.h"

namespace meshmorph::parallel::detail
{

namespace
{

//! The error as its type (first character) and what(); rethrows what is not an Error.
std::string encode(const std::exception_ptr& error)
{
    try
    {
        std::rethrow_exception(error);
    }
    catch (const ParseError& e)
    {
        return std::string("p") + e.what();
    }
    catch (const IoError& e)
    {
        return std::string("i") + e.what();
    }
    catch (const SolverError& e)
    {
        return std::string("s") + e.what();
    }
    catch (const Error& e)
    {
        return std::string("n") + e.what();
    }
}

[[noreturn]] void throw_decoded(const std::string& encoded, int rank)
{
    const std::string where = "processor" + std::to_string(rank);
    const std::string text = encoded.substr(1);
    switch (encoded.front())
    {
    case 'p':
        throw ParseError(where, 0, text);
    case 'i':
        throw IoError(where + ": " + text);
    case 's':
        throw SolverError(where + ": " + text);
    default:
        throw InvalidInput(where + ": " + text);
    }
}

} // namespace

void agree_on_errors(const Communicator& comm, const std::exception_ptr& error)
{
    const std::string mine = error ? encode(error) : std::string();
    if (!comm.any(!mine.empty()))
        return;
    const std::vector<std::string> all = comm.gather(mine);
    int first = -1;
    for (std::size_t r = 0; r < all.size() && first < 0; ++r)
        if (!all[r].empty())
            first = static_cast<int>(r);
    first = comm.broadcast_values(std::vector<int>{first}).front();
    const std::string chosen = comm.broadcast(comm.master() ? all[std::size_t(first)] : "");
    if (first == comm.rank())
        std::rethrow_exception(error);
    throw_decoded(chosen, first);
}

} // namespace meshmorph::parallel::detail
