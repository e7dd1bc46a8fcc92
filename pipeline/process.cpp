// Child processes without a shell.
//
// posix_spawn with an argv vector: the child's file descriptors are set up by file actions
// (stdin from a pipe or /dev/null; stdout and stderr to pipes, to an output file, or inherited),
// its directory by posix_spawn_file_actions_addchdir_np (glibc >= 2.29) and its environment by
// an envp built here. Signals the parent may ignore (SIGPIPE, SIGINT, ...) are reset to their
// defaults in the child and its signal mask is emptied.
//
// The parent's ends of the pipes are pumped with poll(): stdin is written in non-blocking
// chunks while stdout and stderr are read, so a child that fills one pipe while we write the
// other can never deadlock us. Every descriptor we create is O_CLOEXEC, so children started
// side by side (batch workers) do not inherit each other's pipes.
#include "pipeline/process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/error.h"

extern char** environ;

namespace shatter {

namespace {

void close_fd(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
}

[[noreturn]] void throw_start_error(const std::string& program, const std::string& why, const std::string& fix) {
    throw Error(ExitCode::Tool, program + ": cannot start: " + why + " (fix: " + fix + ")");
}

// KEY=VALUE strings: ours, with options.env set or replaced.
std::vector<std::string> child_environment(const std::vector<std::pair<std::string, std::string>>& changes) {
    std::vector<std::string> env;
    for (char** e = environ; e && *e; ++e) env.emplace_back(*e);
    for (const auto& [key, value] : changes) {
        const std::string prefix = key + "=";
        std::erase_if(env, [&](const std::string& s) { return s.compare(0, prefix.size(), prefix) == 0; });
        env.push_back(prefix + value);
    }
    return env;
}

std::vector<char*> c_strings(std::vector<std::string>& strings) {
    std::vector<char*> out;
    for (std::string& s : strings) out.push_back(s.data());
    out.push_back(nullptr);
    return out;
}

// Owns posix_spawn's attribute and file-action objects.
struct SpawnSetup {
    posix_spawn_file_actions_t actions;
    posix_spawnattr_t attr;
    SpawnSetup() {
        posix_spawn_file_actions_init(&actions);
        posix_spawnattr_init(&attr);
        sigset_t none, defaults;
        sigemptyset(&none);
        sigemptyset(&defaults);
        for (int sig : {SIGPIPE, SIGINT, SIGQUIT, SIGTERM, SIGHUP, SIGCHLD, SIGUSR1, SIGUSR2, SIGALRM})
            sigaddset(&defaults, sig);
        posix_spawnattr_setsigmask(&attr, &none);
        posix_spawnattr_setsigdefault(&attr, &defaults);
        posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    }
    ~SpawnSetup() {
        posix_spawn_file_actions_destroy(&actions);
        posix_spawnattr_destroy(&attr);
    }
};

int make_pipe(int fds[2], const std::string& program) {
    if (::pipe2(fds, O_CLOEXEC) != 0) throw_start_error(program, std::strerror(errno), "close some files or processes");
    return 0;
}

// Writes to a pipe whose reader may have gone without SIGPIPE killing us: SIGPIPE is blocked
// in this thread for the write and a SIGPIPE it raised is consumed.
ssize_t write_no_sigpipe(int fd, const char* data, size_t size) {
    sigset_t pipe_set, old_mask, pending;
    sigemptyset(&pipe_set);
    sigaddset(&pipe_set, SIGPIPE);
    sigpending(&pending);
    const bool was_pending = sigismember(&pending, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_set, &old_mask);
    ssize_t n = ::write(fd, data, size);
    const int saved = errno;
    if (n < 0 && saved == EPIPE && !was_pending) {
        const timespec zero{0, 0};
        while (sigtimedwait(&pipe_set, nullptr, &zero) < 0 && errno == EINTR) {
        }
    }
    pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
    errno = saved;
    return n;
}

}  // namespace

std::string own_executable() {
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throw Error(ExitCode::Internal, "cannot find the shatter executable (/proc/self/exe)");
    return p.string();
}

std::string command_line(const std::vector<std::string>& argv) {
    std::string out;
    for (const std::string& a : argv) {
        if (!out.empty()) out += ' ';
        out += '\'';
        for (char c : a) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
        out += '\'';
    }
    return out;
}

std::string last_lines(const std::string& text, size_t count) {
    std::vector<std::string> lines;
    size_t begin = 0;
    while (begin < text.size()) {
        size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(begin, end - begin);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (!line.empty()) lines.push_back(std::move(line));
        begin = end + 1;
    }
    std::string out;
    for (size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i)
        out += (out.empty() ? "" : "\n") + lines[i];
    return out;
}

std::string ProcessResult::describe() const {
    if (signal != 0) {
        const char* name = ::strsignal(signal);
        return "killed by signal " + std::to_string(signal) + " (" + (name ? name : "unknown") + ")";
    }
    return "exit code " + std::to_string(exit_code);
}

// The parent's side of one child: its pipes and what has come out of them so far.
struct ChildProcess::State {
    int stdin_fd = -1, stdout_fd = -1, stderr_fd = -1;
    std::string stdin_data;
    size_t stdin_written = 0;
    bool stdin_stream = false;  // stdin stays open between writes until close_stdin
    ProcessResult result;
    bool reaped = false;

    int open_count() const { return (stdin_fd >= 0) + (stdout_fd >= 0) + (stderr_fd >= 0); }
    bool pipes_open() const { return open_count() > 0; }

    ~State() {
        close_fd(stdin_fd);
        close_fd(stdout_fd);
        close_fd(stderr_fd);
    }

    // One round of I/O: waits up to `timeout_ms` (-1: until something happens) for any pipe.
    void pump(int timeout_ms) {
        pollfd fds[3];
        int n = 0;
        if (stdin_fd >= 0 && stdin_written < stdin_data.size()) fds[n++] = {stdin_fd, POLLOUT, 0};
        if (stdout_fd >= 0) fds[n++] = {stdout_fd, POLLIN, 0};
        if (stderr_fd >= 0) fds[n++] = {stderr_fd, POLLIN, 0};
        if (n == 0) return;
        if (::poll(fds, nfds_t(n), timeout_ms) < 0) return;  // EINTR: the caller loops
        for (int i = 0; i < n; ++i) {
            if (fds[i].revents == 0) continue;
            if (fds[i].fd == stdin_fd)
                write_stdin();
            else
                read_into(fds[i].fd == stdout_fd ? stdout_fd : stderr_fd,
                          fds[i].fd == stdout_fd ? result.out : result.err);
        }
    }

    void write_stdin() {
        const size_t chunk = std::min<size_t>(stdin_data.size() - stdin_written, 65536);
        ssize_t n = write_no_sigpipe(stdin_fd, stdin_data.data() + stdin_written, chunk);
        if (n > 0) stdin_written += size_t(n);
        const bool closed = n < 0 && errno != EAGAIN && errno != EINTR;
        if (closed || (stdin_written == stdin_data.size() && !stdin_stream)) {
            close_fd(stdin_fd);  // done, or the child closed its stdin (EPIPE): it gets no more
            stdin_data.clear();
        }
    }

    static void read_into(int& fd, std::string& sink) {
        char buffer[65536];
        ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n > 0)
            sink.append(buffer, size_t(n));
        else if (n == 0 || (errno != EAGAIN && errno != EINTR))
            close_fd(fd);
    }

    // Records how the child ended; true once it has.
    bool reap(int pid, bool block) {
        if (reaped) return true;
        int status = 0;
        pid_t r;
        do r = ::waitpid(pid, &status, block ? 0 : WNOHANG);
        while (r < 0 && errno == EINTR);
        if (r == 0) return false;
        reaped = true;
        if (r < 0) return true;  // not our child any more: nothing to report
        if (WIFEXITED(status)) {
            result.exit_code = WEXITSTATUS(status);
        } else if (WIFSIGNALED(status)) {
            result.exit_code = -1;
            result.signal = WTERMSIG(status);
        }
        return true;
    }
};

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const ProcessOptions& options) {
    if (argv.empty() || argv[0].empty()) throw Error(ExitCode::Internal, "run_process: empty argv");
    const std::optional<std::string> found = find_program(argv[0]);
    if (!found) throw_start_error(argv[0], "not found on PATH or not executable", "install it or check PATH");
    // The program path stays valid after the child's chdir.
    std::string program = *found;
    if (!options.working_directory.empty() && program[0] != '/')
        program = std::filesystem::absolute(program).string();

    auto state = std::make_unique<State>();
    SpawnSetup setup;
    int in_pipe[2] = {-1, -1}, out_pipe[2] = {-1, -1}, err_pipe[2] = {-1, -1};
    int file_fd = -1;
    auto close_child_ends = [&] {
        close_fd(in_pipe[0]);
        close_fd(out_pipe[1]);
        close_fd(err_pipe[1]);
        close_fd(file_fd);
    };
    try {
        if (options.stdin_data.empty() && !options.stdin_stream) {
            posix_spawn_file_actions_addopen(&setup.actions, 0, "/dev/null", O_RDONLY, 0);
        } else {
            make_pipe(in_pipe, argv[0]);
            posix_spawn_file_actions_adddup2(&setup.actions, in_pipe[0], 0);
            state->stdin_fd = in_pipe[1];
            state->stdin_stream = options.stdin_stream;
            if (!options.stdin_stream) state->stdin_data = options.stdin_data;
            ::fcntl(state->stdin_fd, F_SETFL, ::fcntl(state->stdin_fd, F_GETFL) | O_NONBLOCK);
        }
        if (!options.output_file.empty()) {
            file_fd = ::open(options.output_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
            if (file_fd < 0) throw_io_error(options.output_file, std::strerror(errno));
            posix_spawn_file_actions_adddup2(&setup.actions, file_fd, 1);
            posix_spawn_file_actions_adddup2(&setup.actions, file_fd, 2);
        } else {
            if (options.capture_stdout) {
                make_pipe(out_pipe, argv[0]);
                posix_spawn_file_actions_adddup2(&setup.actions, out_pipe[1], 1);
                state->stdout_fd = out_pipe[0];
            }
            if (options.capture_stderr) {
                make_pipe(err_pipe, argv[0]);
                posix_spawn_file_actions_adddup2(&setup.actions, err_pipe[1], 2);
                state->stderr_fd = err_pipe[0];
            }
        }
        if (!options.working_directory.empty())
            posix_spawn_file_actions_addchdir_np(&setup.actions, options.working_directory.c_str());

        std::vector<std::string> args = argv, env = child_environment(options.env);
        std::vector<char*> c_args = c_strings(args), c_env = c_strings(env);
        pid_t pid = -1;
        const int rc = ::posix_spawn(&pid, program.c_str(), &setup.actions, &setup.attr, c_args.data(), c_env.data());
        if (rc != 0) {
            std::string why = std::strerror(rc);
            if (!options.working_directory.empty()) why += " (working directory " + options.working_directory + ")";
            throw_start_error(program, why, "check that the program and the working directory exist");
        }
        pid_ = pid;
    } catch (...) {
        close_child_ends();
        throw;  // state's destructor closes our ends
    }
    close_child_ends();
    state_ = state.release();
}

ChildProcess::~ChildProcess() {
    if (state_ && !state_->reaped && pid_ > 0) {
        ::kill(pid_, SIGTERM);
        // Two seconds to end politely, then SIGKILL.
        for (int i = 0; i < 200 && !state_->reap(pid_, false); ++i) {
            const timespec ten_ms{0, 10'000'000};
            ::nanosleep(&ten_ms, nullptr);
        }
        if (!state_->reaped) {
            ::kill(pid_, SIGKILL);
            state_->reap(pid_, true);
        }
    }
    delete state_;
}

std::optional<ProcessResult> ChildProcess::poll() {
    // Drain what is ready now (a bounded number of rounds, so a chatty child cannot hold us).
    for (int round = 0; round < 64 && state_->pipes_open(); ++round) {
        const size_t before = state_->result.out.size() + state_->result.err.size() + state_->stdin_written;
        const int open_before = state_->open_count();
        state_->pump(0);
        const size_t after = state_->result.out.size() + state_->result.err.size() + state_->stdin_written;
        if (after == before && open_before == state_->open_count()) break;
    }
    if (state_->pipes_open() || !state_->reap(pid_, false)) return std::nullopt;
    return state_->result;
}

bool ChildProcess::write_stdin(std::string_view data) {
    if (!state_->stdin_stream) throw Error(ExitCode::Internal, "ChildProcess::write_stdin without stdin_stream");
    if (state_->stdin_fd < 0) return false;
    state_->stdin_data.assign(data.data(), data.size());
    state_->stdin_written = 0;
    while (state_->stdin_fd >= 0 && state_->stdin_written < state_->stdin_data.size()) state_->pump(-1);
    state_->stdin_data.clear();
    state_->stdin_written = 0;
    return state_->stdin_fd >= 0;
}

void ChildProcess::close_stdin() {
    close_fd(state_->stdin_fd);
    state_->stdin_data.clear();
}

ProcessResult ChildProcess::wait() {
    if (state_->stdin_stream) close_stdin();
    while (state_->pipes_open()) state_->pump(-1);
    state_->reap(pid_, true);
    return state_->result;
}

ProcessResult run_process(const std::vector<std::string>& argv, const ProcessOptions& options) {
    ChildProcess child(argv, options);
    return child.wait();
}

}  // namespace shatter
