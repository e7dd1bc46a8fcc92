// A library call in a child process. Why: isolated.h.
#include "core/isolated.h"

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <new>
#include <utility>

#include <fmt/format.h>

#include "core/error.h"

namespace shatter {
namespace {

bool write_all(int fd, const void* data, size_t n) {
    const char* p = static_cast<const char*>(data);
    while (n > 0) {
        const ssize_t w = ::write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w, n -= size_t(w);
    }
    return true;
}

// The child's message: 'R' + the result, 'E' + an Error's message, or 'A' (out of memory).
[[noreturn]] void child(const std::function<std::string()>& work, int fd) {
    // A crash in the child ends it with the signal, which the parent reports; no handler of the
    // parent's (a sanitizer's, a crash reporter's) runs in the child.
    for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(s, SIG_DFL);
    std::string out;
    try {
        const std::string result = work();
        out.reserve(result.size() + 1);
        out.push_back('R');
        out += result;
    } catch (const Error& e) {
        out = std::string("E") + e.what();
    } catch (const std::bad_alloc&) {
        out = "A";
    } catch (...) {
        ::_exit(70);
    }
    ::_exit(write_all(fd, out.data(), out.size()) ? 0 : 71);
}

}  // namespace

IsolatedRun::IsolatedRun(const std::function<std::string()>& work, double deadline_seconds)
    : deadline_seconds_(deadline_seconds),
      deadline_(std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                        std::chrono::duration<double>(deadline_seconds))) {
    int fds[2];
    if (::pipe(fds) == 0) {
        std::fflush(nullptr);
        pid_ = ::fork();
        if (pid_ == 0) {
            ::close(fds[0]);
            child(work, fds[1]);
        }
        ::close(fds[1]);
        if (pid_ > 0) {
            fd_ = fds[0];
            return;
        }
        ::close(fds[0]);
    }
    // No child can be made: the work runs here, now.
    try {
        in_process_ = work();
    } catch (...) {
        in_process_error_ = std::current_exception();
    }
}

IsolatedRun::~IsolatedRun() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    ::close(fd_);
    while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
    }
}

std::string IsolatedRun::finish() {
    if (pid_ <= 0) {
        if (in_process_error_) std::rethrow_exception(std::exchange(in_process_error_, nullptr));
        return std::move(in_process_);
    }
    const pid_t pid = std::exchange(pid_, -1);
    std::string bytes;
    char buf[1 << 16];
    bool timed_out = false;
    for (;;) {
        const double left = std::chrono::duration<double>(deadline_ - std::chrono::steady_clock::now()).count();
        pollfd p{fd_, POLLIN, 0};
        const int ready = left > 0 ? ::poll(&p, 1, int(std::min(left * 1e3 + 1, 60e3))) : 0;
        if (ready < 0 && errno == EINTR) continue;
        if (ready == 0) {
            if (left > 0) continue;  // a poll slice of at most a minute ended: look at the clock again
            timed_out = true;
            ::kill(pid, SIGKILL);
            break;
        }
        const ssize_t r = ::read(fd_, buf, sizeof buf);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        bytes.append(buf, size_t(r));
    }
    ::close(fd_);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (timed_out) {
        IsolatedFailure failure(fmt::format("no result within {:g} s", deadline_seconds_));
        failure.timed_out = true;
        throw failure;
    }
    if (WIFSIGNALED(status) || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || bytes.empty())
        throw IsolatedFailure(WIFSIGNALED(status) ? fmt::format("signal {} ({})", WTERMSIG(status),
                                                                strsignal(WTERMSIG(status)))
                                                  : fmt::format("exit code {}", WEXITSTATUS(status)));
    if (bytes[0] == 'E') throw Error(ExitCode::BadInput, bytes.substr(1));
    if (bytes[0] == 'A') throw std::bad_alloc();
    return bytes.substr(1);
}

std::string run_isolated(const std::function<std::string()>& work, double deadline_seconds) {
    return IsolatedRun(work, deadline_seconds).finish();
}

}  // namespace shatter
