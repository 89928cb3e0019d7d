// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Whole-file reads (plain or gzip, transparently) and atomic writes of OpenFOAM files.
//!
//! OpenFOAM opens a file `X` under its plain name if it exists and otherwise `X.gz`
//! (docs/polymesh-format.md §7); these helpers follow the same rule and warn when both
//! exist. Writes go to a temporary file in the target directory which is then renamed over
//! the target, so a reader never sees a half-written file.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace meshmorph::io
{

//! The complete (decompressed) contents of one file.
struct FileBuffer
{
    std::filesystem::path path; //!< the file actually read (`X` or `X.gz`)
    std::string data;           //!< decompressed bytes
    bool is_compressed = false; //!< whether `path` was gzip-compressed
};

//! \brief The file to open for the OpenFOAM name `path`: `path` if it exists, else `path.gz`
//! if that exists, else nothing. Logs a warning when both exist (the plain one wins).
//! A `path` that already ends in `.gz` is returned as is when it exists.
std::optional<std::filesystem::path> resolve_foam_file(const std::filesystem::path& path);

//! Whether `path` or `path.gz` exists as a regular file.
bool foam_file_exists(const std::filesystem::path& path);

//! \brief Read a whole file into memory, `path` or else `path.gz` (see resolve_foam_file).
//! Gzip data is recognised by its magic bytes, so a compressed file without the `.gz`
//! suffix is read too.
//! \throw IoError naming the path if neither file exists, on read errors and on corrupt
//! or truncated gzip data.
FileBuffer read_foam_file(const std::filesystem::path& path);

//! \brief A whole file for parsing without copying: memory-mapped (read-only) when plain,
//! decompressed into memory when gzip. Same X / X.gz rule as read_foam_file. Move-only.
class MappedFoamFile
{
public:
    //! \throw IoError naming the path as read_foam_file.
    explicit MappedFoamFile(const std::filesystem::path& path);
    MappedFoamFile(MappedFoamFile&& other) noexcept;
    MappedFoamFile& operator=(MappedFoamFile&& other) noexcept;
    MappedFoamFile(const MappedFoamFile&) = delete;
    MappedFoamFile& operator=(const MappedFoamFile&) = delete;
    ~MappedFoamFile();

    //! The (decompressed) contents; valid while this object lives.
    std::string_view data() const { return {data_, size_}; }
    //! The file actually read (`X` or `X.gz`).
    const std::filesystem::path& path() const { return path_; }
    bool is_compressed() const { return is_compressed_; }
    //! Release the contents early (data() becomes empty).
    void release();

private:
    std::filesystem::path path_;
    std::string owned_;   // decompressed data of a gzip file
    void* map_ = nullptr; // mmap of a plain file
    std::size_t map_size_ = 0;
    const char* data_ = nullptr;
    std::size_t size_ = 0;
    bool is_compressed_ = false;
};

//! Options of write_file_atomic.
struct WriteFileOptions
{
    bool compress = false;     //!< gzip the data and write `path.gz` instead of `path`
    int compression_level = 6; //!< zlib level 1..9 (OpenFOAM uses the zlib default, 6)
};

//! \brief Write `data` to `path` (or `path.gz` when compressing) atomically: the bytes go to
//! a temporary file in the same directory (temp_file.h), fsync'ed, then renamed over the
//! target and the directory fsync'ed: a reader, a killed run or a power loss sees the old
//! file or the new one, never a partial one. Temporaries of killed runs are removed first.
//! The other spelling (`path.gz` when writing `path`, and vice versa) is removed afterwards so
//! both never coexist. The gzip header carries no time stamp, so equal data gives equal
//! bytes. Returns the path written.
//! \pre the parent directory exists.
//! \throw IoError naming the path on any failure (the target is then left unchanged).
std::filesystem::path write_file_atomic(const std::filesystem::path& path, std::string_view data,
                                        const WriteFileOptions& options = {});

//! \brief Gzip-compress `data` (deterministic gzip header without time stamp).
//! \throw IoError on a zlib failure (`what` names the operation).
std::string gzip_compress(std::string_view data, int level = 6);

//! \brief Decompress a complete gzip stream (concatenated members are accepted).
//! \param name used in error messages (usually the file path).
//! \throw IoError naming `name` on corrupt or truncated data.
std::string gzip_decompress(std::string_view data, const std::string& name);

//! Whether `data` starts with the gzip magic bytes 1f 8b.
bool is_gzip(std::string_view data);

} // namespace meshmorph::io
