// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The target surfaces of `type surface` entries: each file read once, projections by
//! the exact closest point (core/triangle_surface.h, with its tie rule).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "meshmorph/core/triangle_surface.h"
#include "meshmorph/core/types.h"

namespace meshmorph::morph
{

//! Reads target surfaces once per file (paths relative to the case) and projects points
//! onto them (exact closest point, AABB tree).
class SurfaceProjector
{
public:
    explicit SurfaceProjector(std::filesystem::path case_dir) : case_dir_(std::move(case_dir)) {}
    //! \brief The closest points of `file`'s surface to the rows of `query`.
    //! \throw IoError, ParseError for an unreadable surface file.
    Points operator()(const std::string& file, const Points& query);

private:
    std::filesystem::path case_dir_;
    std::map<std::string, std::shared_ptr<SurfaceTree>> trees_;
};

} // namespace meshmorph::morph
