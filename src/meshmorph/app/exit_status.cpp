// SPDX-License-Identifier: GPL-3.0-or-later
// The one catch ladder of the applications.
#include "meshmorph/app/exit_status.h"

#include <ostream>

#include "meshmorph/app/options.h"
#include "meshmorph/core/exceptions.h"

namespace meshmorph::app
{

int run_guarded(const std::function<int()>& body, std::ostream& err, bool nothing_written,
                const FailureHook& on_failure)
{
    const std::string written = nothing_written ? "Nothing written.\n" : "";
    const auto fail = [&](int status, const std::string& message)
    {
        err << message;
        if (on_failure)
            on_failure(status, message);
        return status;
    };
    try
    {
        return body();
    }
    catch (const UsageError& e)
    {
        return fail(exit_input_error, "Error: " + std::string(e.what()) + "\n");
    }
    catch (const SolverError& e)
    {
        return fail(exit_fit_failed, "Error: " + std::string(e.what()) + "\n" + written);
    }
    catch (const Error& e)
    {
        return fail(exit_input_error, "Error: " + std::string(e.what()) + "\n" + written);
    }
    catch (const std::exception& e)
    {
        return fail(exit_internal_error, "Internal error: " + std::string(e.what()) + "\n");
    }
}

} // namespace meshmorph::app
