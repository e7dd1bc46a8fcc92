// Runs a program with an argument vector (never through a shell), capturing its exit code,
// stdout and stderr: what the command-line tests use to drive `shatter` like a user does.
#pragma once

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <algorithm>
#include <string>
#include <vector>

namespace shatter::testing_support {

struct CommandResult {
    int exit_code = -1;
    std::string out;
    std::string err;
};

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline CommandResult run_command(const std::vector<std::string>& args, const std::string& cwd = "") {
    char out_name[] = "/tmp/shatter-out-XXXXXX";
    char err_name[] = "/tmp/shatter-err-XXXXXX";
    int out_fd = ::mkstemp(out_name);
    int err_fd = ::mkstemp(err_name);
    pid_t pid = ::fork();
    if (pid == 0) {
        ::dup2(out_fd, 1);
        ::dup2(err_fd, 2);
        if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(127);
        std::vector<char*> argv;
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    ::close(out_fd);
    ::close(err_fd);
    CommandResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = slurp(out_name);
    r.err = slurp(err_name);
    ::unlink(out_name);
    ::unlink(err_name);
    return r;
}

// `shatter` followed by `args`.
inline CommandResult run_shatter(std::vector<std::string> args, const std::string& cwd = "") {
    args.insert(args.begin(), SHATTER_BINARY);
    return run_command(args, cwd);
}

// What the closing summary's "stages:" line of `shatter run` says of one stage: "render 0.31s"
// when it ran, "render 0.00s (up to date)" when it was skipped; "" when the line has no such stage.
inline std::string stage_status(const std::string& out, const std::string& stage) {
    const size_t line = out.find("stages:");
    if (line == std::string::npos) return "";
    const size_t at = out.find(" " + stage + " ", line);
    if (at == std::string::npos) return "";
    const size_t end = std::min(out.find(',', at), out.find(" (total", at));
    return out.substr(at + 1, end - at - 1);
}

}  // namespace shatter::testing_support
