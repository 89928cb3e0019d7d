// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/deform/rbf_settings.h"

#include <cctype>

#include "meshmorph/core/exceptions.h"

namespace meshmorph
{

std::string to_string(RbfKernel kernel)
{
    switch (kernel)
    {
    case RbfKernel::triharmonic:
        return "triharmonic";
    case RbfKernel::biharmonic:
        return "biharmonic";
    case RbfKernel::polyharmonic:
        return "polyharmonic";
    case RbfKernel::gaussian:
        return "gaussian";
    case RbfKernel::multiquadric:
        return "multiquadric";
    case RbfKernel::inverse_multiquadric:
        return "inverseMultiquadric";
    case RbfKernel::wendland_c2:
        return "wendlandC2";
    }
    return "unknown";
}

RbfKernel rbf_kernel_from_string(const std::string& name)
{
    std::string key;
    for (char c : name)
        if (c != '_')
            key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (RbfKernel k : {RbfKernel::triharmonic, RbfKernel::biharmonic, RbfKernel::polyharmonic,
                        RbfKernel::gaussian, RbfKernel::multiquadric,
                        RbfKernel::inverse_multiquadric, RbfKernel::wendland_c2})
    {
        std::string n;
        for (char c : to_string(k))
            n += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (n == key)
            return k;
    }
    throw InvalidInput("unknown RBF kernel '" + name +
                       "' (expected triharmonic, biharmonic, polyharmonic, gaussian, "
                       "multiquadric, inverseMultiquadric or wendlandC2)");
}

} // namespace meshmorph
