// Running a library call that may crash or not end in a child process.
//
// Debian's assimp 5.2 crashes (SIGSEGV) on some malformed files and its PLY reader could spin for
// ever; CGAL's Mesh_3 dies with SIGBUS inside its feature protection on some surfaces (seen on
// CGAL's own elk.off and on alpha wraps of open meshes). A crash inside a library must not end
// `shatter prescore` with a signal, and an unattended batch must never hang on one mesh. So the
// call runs in a child (fork), which sends its result back through a pipe as bytes; a child that
// dies, or has not finished by its deadline (then it is killed), becomes an IsolatedFailure that
// the caller turns into a clear error or another attempt. The cost is one fork per call.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>

namespace shatter {

// What went wrong in the child: "signal 7 (Bus error)", "exit code 70", "no result within 60 s".
struct IsolatedFailure : std::runtime_error {
    using std::runtime_error::runtime_error;
    bool timed_out = false;
};

// Runs `work` in a child process and returns the bytes it returned. An exception thrown by
// `work` is rethrown here as Error(BadInput) with its message when it was an Error, as
// std::bad_alloc when it was one, and as IsolatedFailure otherwise. Throws IsolatedFailure when
// the child crashed or ran past `deadline_seconds` (it is then killed). When no child can be
// made (no pipe, no fork), `work` runs in this process.
std::string run_isolated(const std::function<std::string()>& work, double deadline_seconds);

// run_isolated begun now and ended by finish(), so that the caller works while the child does
// (prescore simplifies the render surfaces' surface beside the tetrahedralization). The deadline
// counts from the start; finish() returns or throws as run_isolated does, once. A run not
// finished is killed when it goes out of scope (a result that is no longer wanted).
class IsolatedRun {
public:
    IsolatedRun(const std::function<std::string()>& work, double deadline_seconds);
    ~IsolatedRun();
    IsolatedRun(const IsolatedRun&) = delete;
    IsolatedRun& operator=(const IsolatedRun&) = delete;
    std::string finish();

private:
    double deadline_seconds_;
    std::chrono::steady_clock::time_point deadline_;
    pid_t pid_ = -1;
    int fd_ = -1;
    std::string in_process_;                 // the result when no child could be made
    std::exception_ptr in_process_error_;    // or what it threw
};

}  // namespace shatter
