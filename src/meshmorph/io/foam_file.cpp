// SPDX-License-Identifier: GPL-3.0-or-later
// Whole-file reads (plain or gzip) and atomic writes.
#include "meshmorph/io/foam_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <system_error>
#include <utility>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/temp_file.h"

namespace meshmorph::io
{
namespace fs = std::filesystem;

namespace
{

fs::path with_gz(const fs::path& path)
{
    fs::path gz = path;
    gz += ".gz";
    return gz;
}

bool has_gz_suffix(const fs::path& path)
{
    return path.extension() == ".gz";
}

bool is_regular(const fs::path& path)
{
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

struct FileCloser
{
    void operator()(std::FILE* f) const
    {
        if (f != nullptr)
            std::fclose(f);
    }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

std::string errno_text()
{
    return std::strerror(errno);
}

std::string read_raw_file(const fs::path& path)
{
    FilePtr file(std::fopen(path.c_str(), "rb"));
    if (!file)
        throw IoError("Cannot open " + path.string() + ": " + errno_text());
    std::error_code ec;
    const std::uintmax_t size_hint = fs::file_size(path, ec);
    std::string data;
    if (!ec)
        data.resize(static_cast<std::size_t>(size_hint));
    std::size_t got = data.empty() ? 0 : std::fread(data.data(), 1, data.size(), file.get());
    if (got < data.size())
    {
        if (std::ferror(file.get()))
            throw IoError("Cannot read " + path.string() + ": " + errno_text());
        data.resize(got); // the file shrank while reading
    }
    // The file may have grown (or file_size failed): read the rest in chunks.
    char chunk[65536];
    for (;;)
    {
        const std::size_t n = std::fread(chunk, 1, sizeof chunk, file.get());
        data.append(chunk, n);
        if (n < sizeof chunk)
        {
            if (std::ferror(file.get()))
                throw IoError("Cannot read " + path.string() + ": " + errno_text());
            break;
        }
    }
    return data;
}

} // namespace

bool is_gzip(std::string_view data)
{
    return data.size() >= 2 && static_cast<unsigned char>(data[0]) == 0x1f &&
           static_cast<unsigned char>(data[1]) == 0x8b;
}

std::optional<fs::path> resolve_foam_file(const fs::path& path)
{
    const bool plain = is_regular(path);
    if (has_gz_suffix(path))
        return plain ? std::optional<fs::path>(path) : std::nullopt;
    const fs::path gz = with_gz(path);
    const bool compressed = is_regular(gz);
    if (plain && compressed)
        log::warning() << "Both " << path.string() << " and " << gz.string() << " exist; reading "
                       << path.string();
    if (plain)
        return path;
    if (compressed)
        return gz;
    return std::nullopt;
}

bool foam_file_exists(const fs::path& path)
{
    return is_regular(path) || (!has_gz_suffix(path) && is_regular(with_gz(path)));
}

FileBuffer read_foam_file(const fs::path& path)
{
    const std::optional<fs::path> found = resolve_foam_file(path);
    if (!found)
        throw IoError(
            "Cannot find file " + path.string() +
            (has_gz_suffix(path) ? std::string() : " (nor " + with_gz(path).string() + ")"));
    FileBuffer buffer;
    buffer.path = *found;
    buffer.data = read_raw_file(*found);
    if (is_gzip(buffer.data))
    {
        std::string plain = gzip_decompress(buffer.data, found->string());
        // Release the compressed bytes before keeping the plain ones (peak memory).
        std::string().swap(buffer.data);
        buffer.data = std::move(plain);
        buffer.is_compressed = true;
    }
    return buffer;
}

MappedFoamFile::MappedFoamFile(const fs::path& path)
{
    const std::optional<fs::path> found = resolve_foam_file(path);
    if (!found)
        throw IoError(
            "Cannot find file " + path.string() +
            (has_gz_suffix(path) ? std::string() : " (nor " + with_gz(path).string() + ")"));
    path_ = *found;
    const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        throw IoError("Cannot open " + path_.string() + ": " + errno_text());
    struct stat st
    {
    };
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    {
        const std::string why = errno_text();
        ::close(fd);
        throw IoError("Cannot read " + path_.string() + ": " + why);
    }
    map_size_ = static_cast<std::size_t>(st.st_size);
    if (map_size_ > 0)
    {
        // MAP_POPULATE reads the whole file at once: fewer page faults than touching it.
        void* m = ::mmap(nullptr, map_size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (m == MAP_FAILED)
        {
            ::close(fd);
            // Unmappable (special file system): fall back to reading.
            owned_ = read_foam_file(path_).data;
            map_size_ = 0;
            data_ = owned_.data();
            size_ = owned_.size();
            is_compressed_ = false;
            return;
        }
        map_ = m;
        ::madvise(map_, map_size_, MADV_SEQUENTIAL);
    }
    ::close(fd);
    data_ = static_cast<const char*>(map_);
    size_ = map_size_;
    if (is_gzip(std::string_view(data_, size_)))
    {
        owned_ = gzip_decompress(std::string_view(data_, size_), path_.string());
        ::munmap(map_, map_size_);
        map_ = nullptr;
        map_size_ = 0;
        data_ = owned_.data();
        size_ = owned_.size();
        is_compressed_ = true;
    }
}

MappedFoamFile::MappedFoamFile(MappedFoamFile&& other) noexcept
{
    *this = std::move(other);
}

MappedFoamFile& MappedFoamFile::operator=(MappedFoamFile&& other) noexcept
{
    if (this != &other)
    {
        release();
        path_ = std::move(other.path_);
        is_compressed_ = other.is_compressed_;
        map_ = std::exchange(other.map_, nullptr);
        map_size_ = std::exchange(other.map_size_, 0);
        const bool owned = other.data_ != nullptr && other.data_ == other.owned_.data();
        owned_ = std::move(other.owned_);
        data_ = owned ? owned_.data() : other.data_;
        size_ = other.size_;
        other.data_ = nullptr;
        other.size_ = 0;
    }
    return *this;
}

MappedFoamFile::~MappedFoamFile()
{
    release();
}

void MappedFoamFile::release()
{
    if (map_ != nullptr)
        ::munmap(map_, map_size_);
    map_ = nullptr;
    map_size_ = 0;
    std::string().swap(owned_);
    data_ = nullptr;
    size_ = 0;
}

std::string gzip_decompress(std::string_view data, const std::string& name)
{
    z_stream zs{};
    // 15 + 32: zlib or gzip, detected from the header.
    if (inflateInit2(&zs, 15 + 32) != Z_OK)
        throw IoError("Cannot decompress " + name + ": zlib initialisation failed");
    std::unique_ptr<z_stream, int (*)(z_stream*)> guard(&zs, inflateEnd);

    std::string out;
    // The gzip trailer stores the size modulo 2^32; trust it only up to deflate's maximum
    // ratio (about 1032:1) so that hostile input cannot trigger a huge reservation.
    if (data.size() >= 18)
    {
        std::uint32_t isize = 0;
        std::memcpy(&isize, data.data() + data.size() - 4, 4);
        const std::size_t cap = data.size() * 1032;
        // One spare byte lets inflate finish without a last (doubling) reallocation.
        out.resize(std::min<std::size_t>(isize, cap) + 1);
    }

    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    std::size_t remaining_in = data.size();
    constexpr std::size_t max_chunk = 1u << 30; // zlib counts in uInt
    std::size_t produced = 0;
    for (;;)
    {
        if (zs.avail_in == 0)
        {
            const std::size_t n = std::min(remaining_in, max_chunk);
            zs.avail_in = static_cast<uInt>(n);
            remaining_in -= n;
        }
        if (produced == out.size())
            out.resize(out.size() + std::max<std::size_t>(out.size() / 2, 1u << 20));
        const std::size_t space = std::min(out.size() - produced, max_chunk);
        zs.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
        zs.avail_out = static_cast<uInt>(space);
        const int rc = inflate(&zs, Z_NO_FLUSH);
        produced += space - zs.avail_out;
        if (rc == Z_STREAM_END)
        {
            if (zs.avail_in == 0 && remaining_in == 0)
                break;
            // Concatenated gzip members, as `cat a.gz b.gz` makes.
            if (inflateReset(&zs) != Z_OK)
                throw IoError("Cannot decompress " + name + ": zlib reset failed");
            continue;
        }
        if (rc == Z_BUF_ERROR && zs.avail_in == 0 && remaining_in == 0)
            throw IoError("Cannot decompress " + name + ": truncated gzip data");
        if (rc != Z_OK && rc != Z_BUF_ERROR)
            throw IoError("Cannot decompress " + name + ": corrupt gzip data" +
                          (zs.msg != nullptr ? std::string(" (") + zs.msg + ")" : std::string()));
    }
    out.resize(produced);
    if (out.capacity() > produced + produced / 8 + 4096)
        out.shrink_to_fit(); // only when the size hint was far off (it copies)
    return out;
}

std::string gzip_compress(std::string_view data, int level)
{
    z_stream zs{};
    // 15 + 16: gzip wrapper; deflate writes a header with time stamp 0 (deterministic).
    if (deflateInit2(&zs, std::clamp(level, 1, 9), Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) !=
        Z_OK)
        throw IoError("gzip compression: zlib initialisation failed");
    std::unique_ptr<z_stream, int (*)(z_stream*)> guard(&zs, deflateEnd);
    std::string out;
    out.reserve(data.size() / 3 + 1024);
    constexpr std::size_t max_chunk = 1u << 30; // zlib counts in uInt
    std::size_t in_pos = 0;
    char buf[1 << 16];
    int rc = Z_OK;
    while (rc != Z_STREAM_END)
    {
        if (zs.avail_in == 0 && in_pos < data.size())
        {
            const std::size_t n = std::min(data.size() - in_pos, max_chunk);
            zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data() + in_pos));
            zs.avail_in = static_cast<uInt>(n);
            in_pos += n;
        }
        zs.next_out = reinterpret_cast<Bytef*>(buf);
        zs.avail_out = sizeof buf;
        rc = deflate(&zs, in_pos == data.size() ? Z_FINISH : Z_NO_FLUSH);
        if (rc == Z_STREAM_ERROR)
            throw IoError("gzip compression failed");
        out.append(buf, sizeof buf - zs.avail_out);
    }
    return out;
}

fs::path write_file_atomic(const fs::path& path, std::string_view data,
                           const WriteFileOptions& options)
{
    fs::path target = path;
    fs::path other;
    if (options.compress)
    {
        if (!has_gz_suffix(target))
            target = with_gz(target);
        other = target;
        other.replace_extension(); // strip ".gz"
    }
    else
    {
        if (has_gz_suffix(target))
            throw IoError("Cannot write uncompressed data to " + target.string());
        other = with_gz(target);
    }

    std::string compressed;
    if (options.compress)
        compressed = gzip_compress(data, options.compression_level);
    const std::string_view bytes = options.compress ? std::string_view(compressed) : data;

    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    remove_stale_temps(target); // a killed run's leftovers must not pile up
    const fs::path temp = temp_path_for(target);
    write_synced(temp, bytes, target);
    std::error_code ec;
    fs::rename(temp, target, ec);
    if (ec)
    {
        std::error_code ignored;
        fs::remove(temp, ignored);
        throw IoError("Cannot write " + target.string() + ": rename failed: " + ec.message());
    }
    sync_directory(dir);
    if (is_regular(other))
    {
        fs::remove(other, ec);
        if (ec)
            throw IoError("Wrote " + target.string() + " but cannot remove " + other.string() +
                          ": " + ec.message());
    }
    return target;
}

} // namespace meshmorph::io
