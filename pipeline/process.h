// Running external programs (ffmpeg, python3, sbatch, our own `shatter` for batch workers)
// without a shell: argv vectors through posix_spawn, so that no file name can smuggle in a
// command (spaces, quotes, $(...), backticks, semicolons, newlines are plain bytes).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/find_program.h"  // find_program, with the processes it starts

namespace shatter {

// The path of the running `shatter` (/proc/self/exe), for starting more of it: batch workers,
// cluster jobs.
std::string own_executable();

// For messages: argv as one could paste it into a shell, each argument single-quoted.
std::string command_line(const std::vector<std::string>& argv);

// For messages: the last `count` non-empty lines of a tool's output.
std::string last_lines(const std::string& text, size_t count);

struct ProcessOptions {
    std::string stdin_data;           // written to the child's stdin (then closed); "" = /dev/null
    bool stdin_stream = false;        // a pipe that ChildProcess::write_stdin feeds as data comes, until
                                      // close_stdin (stdin_data is ignored)
    bool capture_stdout = true;       // into ProcessResult::out; false: inherit ours
    bool capture_stderr = true;       // into ProcessResult::err; false: inherit ours
    std::string output_file;          // when set: stdout and stderr both appended to it (capture_* ignored)
    std::vector<std::pair<std::string, std::string>> env;  // set (or replace) in the child's environment
    std::string working_directory;    // "" = ours
};

struct ProcessResult {
    int exit_code = -1;   // when it exited; -1 when killed by a signal
    int signal = 0;       // the signal that killed it, or 0
    std::string out, err; // captured output
    bool ok() const { return exit_code == 0; }
    std::string describe() const;  // "exit code 3" / "killed by signal 9 (Killed)"
};

// Runs argv[0] (looked up with find_program) with argv and waits, feeding stdin and reading both
// pipes as they fill (no deadlock however much each side writes). Throws Error(Tool) when the
// program is not found or cannot be started (including a missing working directory), Error(Io)
// when output_file cannot be opened.
ProcessResult run_process(const std::vector<std::string>& argv, const ProcessOptions& options = {});

// A child started without waiting (batch workers). The destructor kills a child still running
// (SIGTERM, then SIGKILL after 2 s) and reaps it. A child whose output is captured blocks once a
// pipe holds 64 KiB until the next poll(); for chatty workers poll often or use output_file.
// A child counts as ended once it has exited and its captured pipes are closed (a grandchild
// that inherited them keeps them open).
class ChildProcess {
public:
    ChildProcess(const std::vector<std::string>& argv, const ProcessOptions& options);
    ~ChildProcess();
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;
    int pid() const { return pid_; }
    // With ProcessOptions::stdin_stream: writes `data` to the child's stdin, reading its output
    // meanwhile (no deadlock); false when the child has closed its stdin (it gets no more).
    bool write_stdin(std::string_view data);
    // The end of the stream: the child reads end of file (wait() closes it too).
    void close_stdin();
    // Non-blocking: the result once it has ended (captured output is read when it ends).
    std::optional<ProcessResult> poll();
    ProcessResult wait();

private:
    int pid_ = -1;
    // implementation details (pipes, collected output) as the implementation needs
    struct State;
    State* state_ = nullptr;
};

}  // namespace shatter
