// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/io/decomposed_case.h"

#include <algorithm>
#include <cstdint>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/parallel/collective.h"

namespace fs = std::filesystem;

namespace meshmorph::io
{

namespace
{

//! The number of processor<N> directories; refuses the collated processors<N>.
std::size_t count_processor_directories(const fs::path& case_dir, const std::string& tool)
{
    std::size_t n = 0;
    for (const std::string& name : processor_directories(case_dir))
    {
        if (name.starts_with("processors"))
            throw InvalidInput((case_dir / name).string() +
                               " is the collated layout (decomposePar -fileHandler collated), "
                               "which " +
                               tool + " does not read yet: decompose with -fileHandler uncollated");
        ++n;
    }
    return n;
}

} // namespace

fs::path processor_case(const fs::path& case_dir, const parallel::Communicator& comm,
                        const std::string& tool)
{
    const fs::path dir = case_dir / ("processor" + std::to_string(comm.rank()));
    parallel::collective(comm,
                         [&]
                         {
                             if (!fs::is_directory(dir))
                                 throw IoError(dir.string() +
                                               " does not exist: -parallel needs a decomposed case "
                                               "(decomposePar) with one processor directory per "
                                               "rank");
                         });
    parallel::on_master(comm,
                        [&]
                        {
                            const std::size_t n = count_processor_directories(case_dir, tool);
                            if (n != std::size_t(comm.size()))
                                throw InvalidInput("the case has " + std::to_string(n) +
                                                   " processor directories but the run has " +
                                                   std::to_string(comm.size()) +
                                                   " ranks: run mpirun -np " + std::to_string(n) +
                                                   " (or decompose again for " +
                                                   std::to_string(comm.size()) + ")");
                        });
    return dir;
}

std::vector<std::string> processor_directories(const fs::path& case_dir)
{
    std::vector<std::string> dirs;
    for (const fs::directory_entry& e : fs::directory_iterator(case_dir))
        if (e.is_directory() && e.path().filename().string().starts_with("processor"))
            dirs.push_back(e.path().filename().string());
    std::sort(dirs.begin(), dirs.end());
    return dirs;
}

std::vector<Index> read_point_addressing(const FoamPolyMesh& foam)
{
    const fs::path file = foam.faces_dir / "pointProcAddressing";
    std::vector<Index> labels = read_label_list_file(file, "pointProcAddressing");
    if (Index(labels.size()) != foam.mesh.n_points())
        throw InvalidInput(file.string() + " has " + std::to_string(labels.size()) +
                           " labels for " + std::to_string(foam.mesh.n_points()) +
                           " points: decompose the case again");
    return labels;
}

Index global_point_count(const std::vector<Index>& point_addressing,
                         const parallel::Communicator& comm)
{
    std::int64_t largest = -1;
    for (Index g : point_addressing)
        largest = std::max<std::int64_t>(largest, g);
    return Index(comm.max(largest) + 1);
}

} // namespace meshmorph::io
