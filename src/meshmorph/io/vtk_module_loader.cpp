// SPDX-License-Identifier: GPL-3.0-or-later
// The VTK module, loaded by dlopen when a run first writes VTK.
#include "meshmorph/io/vtk_module_loader.h"

#include <dlfcn.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "meshmorph/core/exceptions.h"

namespace meshmorph::io
{

namespace
{

//! The module's entry point, or nullptr with the reasons appended to `why`.
VtkSerialise load_from(const std::string& path, std::string& why)
{
    // RTLD_LOCAL: VTK's symbols stay the module's; RTLD_NOW: a missing library shows here.
    void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (module == nullptr)
    {
        const char* e = ::dlerror();
        why += "\n    " + path + ": " + (e ? e : "not loadable");
        return nullptr;
    }
    void* entry = ::dlsym(module, vtk_serialise_symbol);
    if (entry == nullptr)
    {
        why += "\n    " + path + ": no entry point " + vtk_serialise_symbol;
        return nullptr;
    }
    return reinterpret_cast<VtkSerialise>(entry);
}

//! Where the module may be: beside an installed executable (<prefix>/bin/../lib/meshmorph,
//! wherever the prefix was moved or installed to; first, so that an installed executable
//! never loads the module of the build tree it came from), the build tree (a build is run
//! from there), the configured installation.
std::vector<std::filesystem::path> module_candidates()
{
    std::vector<std::filesystem::path> paths;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec)
        paths.push_back(exe.parent_path().parent_path() / MESHMORPH_VTK_MODULE_INSTALL_SUBPATH);
    paths.emplace_back(MESHMORPH_VTK_MODULE_BUILD_PATH);
    paths.emplace_back(MESHMORPH_VTK_MODULE_INSTALL_PATH);
    return paths;
}

VtkSerialise load()
{
    std::string why;
    for (const std::filesystem::path& path : module_candidates())
        if (std::filesystem::exists(path))
        {
            if (VtkSerialise f = load_from(path.string(), why))
                return f;
        }
        else
            why += "\n    " + path.string() + ": no such file";
    throw IoError("VTK output needs meshmorph's VTK module, which did not load:" + why +
                  "\n(build the target meshmorph_vtk, or install the project)");
}

} // namespace

VtkSerialise vtk_serialiser()
{
    static const VtkSerialise entry = load(); // once; a failure is retried on the next call
    return entry;
}

} // namespace meshmorph::io
