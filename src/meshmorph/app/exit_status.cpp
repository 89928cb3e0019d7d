// SPDX-License-Identifier: GPL-3.0-or-later
// The one catch ladder of the applications.
#include "meshmorph/app/exit_status.h"

#include <new>

#include "meshmorph/app/usage_error.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"

namespace meshmorph::app
{

int run_guarded(const std::function<int()>& body, bool nothing_written,
                const FailureHook& on_failure)
{
    const std::string written = nothing_written ? "\nNothing written." : "";
    const auto fail = [&](int status, const std::string& message)
    {
        log::error() << message;
        if (on_failure)
            on_failure(status, "Error: " + message + "\n");
        return status;
    };
    try
    {
        return body();
    }
    catch (const UsageError& e)
    {
        return fail(exit_input_error, e.what());
    }
    catch (const SolverError& e)
    {
        return fail(exit_fit_failed, e.what() + written);
    }
    catch (const Error& e)
    {
        return fail(exit_input_error, e.what() + written);
    }
    catch (const std::bad_alloc&)
    {
        // The last resort: the up-front estimates (memory_budget.h) did not foresee it.
        return fail(exit_input_error,
                    "out of memory: the mesh or the dictionary asks for more memory than this "
                    "process may allocate (MemAvailable, ulimit -v)" +
                        written);
    }
    catch (const std::exception& e)
    {
        return fail(exit_internal_error,
                    "internal error (please report it): " + std::string(e.what()));
    }
}

} // namespace meshmorph::app
