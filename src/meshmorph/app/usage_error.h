// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The error of a bad command line, which every application reports the same way
//! (exit_status.h: exit_input_error).
#pragma once

#include "meshmorph/core/exceptions.h"

namespace meshmorph::app
{

//! A bad command line (unknown option, missing or malformed argument).
class UsageError : public InvalidInput
{
public:
    using InvalidInput::InvalidInput;
};

} // namespace meshmorph::app
