// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Errors that stay collective: a rank that fails must not leave the others waiting in
//! the next MPI call.
//!
//! collective(comm, f) runs f on every rank; if it throws a meshmorph::Error on any rank,
//! every rank throws the error of the lowest failing rank (same type and message, prefixed
//! "processor<N>: " when it came from another rank). on_master(comm, f) runs f on the master
//! only, with the same rule. Both are collectives: call them on every rank.
#pragma once

#include <exception>
#include <functional>
#include <string>

#include "meshmorph/parallel/communicator.h"

namespace meshmorph::parallel
{

namespace detail
{
//! Every rank: nothing if no rank failed, else throws the lowest failing rank's error (that
//! rank rethrows its own). A failure that is not a meshmorph::Error propagates at once.
void agree_on_errors(const Communicator& comm, const std::exception_ptr& error);
} // namespace detail

//! \brief f() on every rank, errors made collective (see the file comment).
template <class F> void collective(const Communicator& comm, F&& f)
{
    if (!comm.is_parallel())
    {
        f();
        return;
    }
    std::exception_ptr failure;
    try
    {
        f();
    }
    catch (...)
    {
        failure = std::current_exception();
    }
    detail::agree_on_errors(comm, failure);
}

//! \brief f() on the master only, its error (if any) thrown on every rank.
template <class F> void on_master(const Communicator& comm, F&& f)
{
    collective(comm,
               [&]
               {
                   if (comm.master())
                       f();
               });
}

} // namespace meshmorph::parallel
