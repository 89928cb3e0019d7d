// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Test helper: a snapshot of a directory tree (every file's size and content hash,
//! every directory, every symlink), to assert that a failed run left a case byte-identical.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace meshmorph::test
{

//! Relative path -> "dir", "link -> target" or "file <size> <FNV-1a 64 of the bytes>".
using TreeSnapshot = std::map<std::string, std::string>;

inline std::string fnv1a_64(const std::filesystem::path& file)
{
    std::ifstream in(file, std::ios::binary);
    std::uint64_t h = 14695981039346656037ull;
    char buf[65536];
    std::uint64_t size = 0;
    while (in.read(buf, sizeof buf) || in.gcount() > 0)
    {
        for (std::streamsize i = 0; i < in.gcount(); ++i)
            h = (h ^ static_cast<unsigned char>(buf[i])) * 1099511628211ull;
        size += static_cast<std::uint64_t>(in.gcount());
    }
    std::ostringstream s;
    s << "file " << size << ' ' << std::hex << h;
    return s.str();
}

//! \brief Everything under `root` (hidden files too).
inline TreeSnapshot snapshot_tree(const std::filesystem::path& root)
{
    namespace fs = std::filesystem;
    TreeSnapshot snap;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(root))
    {
        const std::string rel = fs::relative(e.path(), root).string();
        if (e.is_symlink())
            snap[rel] = "link -> " + fs::read_symlink(e.path()).string();
        else if (e.is_directory())
            snap[rel] = "dir";
        else
            snap[rel] = fnv1a_64(e.path());
    }
    return snap;
}

//! The differences between two snapshots, one line each ("" when equal).
inline std::string tree_diff(const TreeSnapshot& before, const TreeSnapshot& after)
{
    std::string diff;
    for (const auto& [path, what] : before)
    {
        const auto it = after.find(path);
        if (it == after.end())
            diff += "removed " + path + "\n";
        else if (it->second != what)
            diff += "changed " + path + ": " + what + " -> " + it->second + "\n";
    }
    for (const auto& [path, what] : after)
        if (before.count(path) == 0)
            diff += "added " + path + " (" + what + ")\n";
    return diff;
}

} // namespace meshmorph::test
