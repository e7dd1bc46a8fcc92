// Errors a user can cause (bad input, unwritable output) are thrown as shatter::Error, which
// carries the exit code the command ends with. Our own bugs are assertions, never an Error.
#pragma once

#include <stdexcept>
#include <string>

namespace shatter {

// Exit codes of every `shatter` command (the README lists them).
enum class ExitCode : int {
    Ok = 0,
    Differs = 1,     // `shatter diff`: images differ beyond tolerance; batch/submit: a job failed
    Usage = 2,       // unknown flag, missing argument, flag value out of range
    BadInput = 3,    // unreadable, corrupt or invalid input file (mesh, shot, stage file)
    Io = 4,          // an output cannot be written (permissions, full disk)
    Unstable = 5,    // the simulation went unstable (NaN, runaway energy)
    Tool = 6,        // an external tool (ffmpeg, sbatch) is missing or failed
    Internal = 70,   // a bug in shatter
};

class Error : public std::runtime_error {
public:
    Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    ExitCode code() const { return code_; }

private:
    ExitCode code_;
};

// Bad input: `where` names the file (and line, or field), `problem` says what is wrong with
// which value, `fix` says what to do. Message: "WHERE: PROBLEM (fix: FIX)".
[[noreturn]] void throw_input_error(const std::string& where, const std::string& problem,
                                    const std::string& fix);

// An output that cannot be written; `path` is the file, `reason` what the system said.
[[noreturn]] void throw_io_error(const std::string& path, const std::string& reason);

}  // namespace shatter
