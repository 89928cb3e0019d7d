// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Basic scalar, index and point-array types shared by every module.
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "meshmorph/core/config.h"

namespace meshmorph
{

//! Mesh index (OpenFOAM's `label`): 32-bit unless built with MESHMORPH_LABEL64.
#if MESHMORPH_LABEL64
using Index = std::int64_t;
#else
using Index = std::int32_t;
#endif

using Scalar = double;

//! n x 3 point (or displacement) array, xyz contiguous so raw buffers map without copying.
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

using Vector3 = Eigen::Vector3d;

//! OpenFOAM's numerical constants (src/OpenFOAM/primitives/Scalar/doubleScalar).
namespace constants
{
inline constexpr double small = 1e-15;
inline constexpr double vsmall = 1e-300;
inline constexpr double rootvsmall = 1e-150;
inline constexpr double great = 1e15;
inline constexpr double vgreat = 1e300;
inline constexpr double rootvgreat = 1e150;
} // namespace constants

} // namespace meshmorph
