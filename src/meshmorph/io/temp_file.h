// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The temporary files of atomic writes (foam_file.h): names unique per host, process
//! and write; durable contents (fsync) before the rename; and the removal of temporaries a
//! killed run left behind.
//!
//! A temporary of target `dir/X` is `dir/.X.<host>.<pid>.<n>.tmp`: hidden (OpenFOAM and
//! ls skip it), in the target's directory (rename stays within one file system), never
//! the name of a live writer.
#pragma once

#include <filesystem>
#include <string_view>

namespace meshmorph::io
{

//! \brief A fresh temporary name for `target` (see the file comment).
std::filesystem::path temp_path_for(const std::filesystem::path& target);

//! \brief From now on SIGINT, SIGTERM and SIGHUP first remove the temporary files this
//! process named with temp_path_for (the last 64; renamed ones are gone already), then end
//! the process as the signal would have (an interrupted run leaves no 87 MB temporary of a
//! design basis behind). A staged directory is left to remove_stale_temps of a later run.
void remove_temps_on_interrupt();

//! \brief Remove the temporaries of `target` (files, or directories staged whole) whose writer, a
//! process of this host, is dead (a run killed while writing). Those of other hosts (a shared file
//! system) and of live processes are left alone. Returns how many were removed; never throws.
int remove_stale_temps(const std::filesystem::path& target);

//! \brief Create `path` (it must not exist), write `bytes`, fsync and close it.
//! \throw IoError naming `target` and the reason; `path` is then removed.
void write_synced(const std::filesystem::path& path, std::string_view bytes,
                  const std::filesystem::path& target);

//! \brief fsync the directory `dir`, so that a rename in it survives a power loss.
//! Failures are ignored (some file systems refuse to sync directories).
void sync_directory(const std::filesystem::path& dir);

} // namespace meshmorph::io
