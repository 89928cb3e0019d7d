// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Test helper: run an application as a child process (fork + exec), with its stdout
//! and stderr captured, an optional address-space limit (RLIMIT_AS, as `ulimit -v`) and a
//! timeout. Used where an in-process run cannot show the behaviour: exit status of the
//! real executable, memory limits, signals.
#pragma once

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace meshmorph::test
{

struct ProcessRun
{
    int status = -1; //!< exit status; -N when killed by signal N
    std::string out; //!< stdout
    std::string err; //!< stderr
    bool timed_out = false;
};

struct ProcessOptions
{
    std::size_t address_space_bytes = 0;  //!< RLIMIT_AS of the child; 0: unchanged
    double timeout_seconds = 120;         //!< SIGKILL after this long
    std::vector<std::string> environment; //!< "NAME=value" set in the child
};

namespace detail
{
//! Appends what is readable on `fd` to `to`; false at end of file.
inline bool drain(int fd, std::string& to)
{
    char buf[65536];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0)
        to.append(buf, static_cast<std::size_t>(n));
    return n > 0;
}
} // namespace detail

//! \brief Runs `argv` (argv[0] is the executable's path) and waits for it.
inline ProcessRun run_process(const std::vector<std::string>& argv,
                              const ProcessOptions& options = {})
{
    int out_pipe[2], err_pipe[2];
    if (::pipe(out_pipe) != 0 || ::pipe(err_pipe) != 0)
        std::abort();
    std::vector<char*> args;
    for (const std::string& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0)
    {
        ::dup2(out_pipe[1], 1);
        ::dup2(err_pipe[1], 2);
        for (int fd : {out_pipe[0], out_pipe[1], err_pipe[0], err_pipe[1]})
            ::close(fd);
        for (const std::string& e : options.environment)
            ::putenv(const_cast<char*>(e.c_str()));
        if (options.address_space_bytes > 0)
        {
            const rlimit limit{options.address_space_bytes, options.address_space_bytes};
            ::setrlimit(RLIMIT_AS, &limit);
        }
        ::execv(args[0], args.data());
        ::_exit(127);
    }
    ::close(out_pipe[1]);
    ::close(err_pipe[1]);
    ProcessRun run;
    pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(options.timeout_seconds);
    int open = 2;
    while (open > 0)
    {
        if (std::chrono::steady_clock::now() > deadline && !run.timed_out)
        {
            run.timed_out = true;
            ::kill(pid, SIGKILL);
        }
        if (::poll(fds, 2, 200) <= 0)
            continue;
        for (int k = 0; k < 2; ++k)
            if (fds[k].fd >= 0 && (fds[k].revents & (POLLIN | POLLHUP)) != 0 &&
                !detail::drain(fds[k].fd, k == 0 ? run.out : run.err))
            {
                ::close(fds[k].fd);
                fds[k].fd = -1;
                --open;
            }
    }
    int wstatus = 0;
    ::waitpid(pid, &wstatus, 0);
    run.status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -WTERMSIG(wstatus);
    return run;
}

//! A child process whose stdout is read as it runs, to act at a given moment (SIGKILL).
class SpawnedProcess
{
public:
    //! Starts `argv`; stderr goes to /dev/null.
    explicit SpawnedProcess(const std::vector<std::string>& argv)
    {
        int out_pipe[2];
        if (::pipe(out_pipe) != 0)
            std::abort();
        std::vector<char*> args;
        for (const std::string& a : argv)
            args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        pid_ = ::fork();
        if (pid_ == 0)
        {
            ::dup2(out_pipe[1], 1);
            ::close(out_pipe[0]);
            ::close(out_pipe[1]);
            std::FILE* null = std::freopen("/dev/null", "w", stderr);
            (void)null;
            ::execv(args[0], args.data());
            ::_exit(127);
        }
        ::close(out_pipe[1]);
        out_ = out_pipe[0];
    }
    SpawnedProcess(const SpawnedProcess&) = delete;
    SpawnedProcess& operator=(const SpawnedProcess&) = delete;
    ~SpawnedProcess()
    {
        if (pid_ > 0)
        {
            ::kill(pid_, SIGKILL);
            wait();
        }
    }

    //! Reads stdout until it holds `text` (true) or ends (false).
    bool wait_for_output(const std::string& text)
    {
        while (output_.find(text) == std::string::npos)
            if (!detail::drain(out_, output_))
                return false;
        return true;
    }

    void kill(int signal) { ::kill(pid_, signal); }

    //! Waits for the end; exit status, or -N when killed by signal N.
    int wait()
    {
        std::string rest;
        while (detail::drain(out_, rest))
            ;
        output_ += rest;
        ::close(out_);
        int wstatus = 0;
        ::waitpid(pid_, &wstatus, 0);
        pid_ = -1;
        return WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -WTERMSIG(wstatus);
    }

    const std::string& output() const { return output_; }

private:
    pid_t pid_ = -1;
    int out_ = -1;
    std::string output_;
};

} // namespace meshmorph::test
