// SPDX-License-Identifier: GPL-3.0-or-later
// Temporary files of atomic writes (see temp_file.h).
#include "meshmorph/io/temp_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include "meshmorph/core/exceptions.h"

namespace meshmorph::io
{
namespace fs = std::filesystem;

namespace
{

std::atomic<unsigned> temp_counter{0};

//! The temporaries this process named last, for the signal handler: a ring of fixed slots
//! (a handler may not allocate or lock). A slot is published by its `ready` flag after its
//! name is complete, and withdrawn before it is overwritten. 64 slots: a run has at most a
//! few writes in flight, and an older name was renamed or removed long ago (its unlink then
//! fails harmlessly).
constexpr std::size_t ring_slots = 64;
constexpr std::size_t slot_bytes = 4096;
struct TempSlot
{
    std::atomic<bool> ready{false};
    char name[slot_bytes] = {};
};
TempSlot ring[ring_slots];
std::atomic<std::size_t> ring_next{0};

void remember_temp(const fs::path& temp)
{
    const std::string& name = temp.native();
    if (name.size() >= slot_bytes)
        return; // such a temporary is left to remove_stale_temps
    TempSlot& slot = ring[ring_next.fetch_add(1) % ring_slots];
    slot.ready.store(false);
    std::memcpy(slot.name, name.c_str(), name.size() + 1);
    slot.ready.store(true);
}

extern "C" void remove_temps_and_reraise(int sig)
{
    for (TempSlot& slot : ring)
        if (slot.ready.load())
            ::unlink(slot.name); // async-signal-safe; fails for renamed ones
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

std::string host_name()
{
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0')
        return "localhost";
    std::string host(name);
    for (char& c : host) // a file name part: no separators
        if (c == '/' || c == '.')
            c = '_';
    return host;
}

//! Whether `text` is a non-empty run of decimal digits.
bool all_digits(std::string_view text)
{
    return !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
}

//! The pid of a temporary of ours named `name` for `prefix` (".X.<host>."), or 0.
pid_t temp_writer(const std::string& name, const std::string& prefix)
{
    const std::string suffix = ".tmp";
    if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix))
        return 0;
    const std::string_view middle = std::string_view(name).substr(
        prefix.size(), name.size() - prefix.size() - suffix.size()); // "<pid>.<n>"
    const std::size_t dot = middle.find('.');
    if (dot == std::string_view::npos || !all_digits(middle.substr(0, dot)) ||
        !all_digits(middle.substr(dot + 1)) || dot > 9)
        return 0;
    return static_cast<pid_t>(std::stol(std::string(middle.substr(0, dot))));
}

std::string errno_text()
{
    return std::strerror(errno);
}

} // namespace

fs::path temp_path_for(const fs::path& target)
{
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    fs::path temp = dir / ("." + target.filename().string() + "." + host_name() + "." +
                           std::to_string(::getpid()) + "." +
                           std::to_string(temp_counter.fetch_add(1)) + ".tmp");
    remember_temp(fs::absolute(temp));
    return temp;
}

void remove_temps_on_interrupt()
{
    struct sigaction action = {};
    action.sa_handler = remove_temps_and_reraise;
    sigemptyset(&action.sa_mask);
    for (int sig : {SIGINT, SIGTERM, SIGHUP})
    {
        struct sigaction old = {};
        // A signal the caller's parent set to be ignored (nohup, a shell's background job)
        // stays ignored.
        if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN)
            continue;
        ::sigaction(sig, &action, nullptr);
    }
}

int remove_stale_temps(const fs::path& target)
{
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    const std::string prefix = "." + target.filename().string() + "." + host_name() + ".";
    int removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    {
        const pid_t pid = temp_writer(it->path().filename().string(), prefix);
        // kill(pid, 0) fails with ESRCH only when no such process exists.
        if (pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH)
        {
            std::error_code ignored; // a file, or the staging directory of a new time
            removed += fs::remove_all(it->path(), ignored) > 0 ? 1 : 0;
        }
    }
    return removed;
}

void write_synced(const fs::path& path, std::string_view bytes, const fs::path& target)
{
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0)
        throw IoError("Cannot write " + target.string() + ": cannot create temporary " +
                      path.string() + ": " + errno_text());
    std::string why;
    for (std::size_t done = 0; done < bytes.size() && why.empty();)
    {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno != EINTR)
            why = errno_text();
        else if (n > 0)
            done += static_cast<std::size_t>(n);
    }
    // The data must be on disk before the rename makes it the target: otherwise a crash
    // of the machine can leave the new name with empty or partial contents.
    if (why.empty() && ::fsync(fd) != 0)
        why = errno_text();
    if (::close(fd) != 0 && why.empty())
        why = errno_text();
    if (!why.empty())
    {
        std::error_code ignored;
        fs::remove(path, ignored);
        throw IoError("Cannot write " + target.string() + ": " + why);
    }
}

void sync_directory(const fs::path& dir)
{
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return;
    ::fsync(fd);
    ::close(fd);
}

} // namespace meshmorph::io
