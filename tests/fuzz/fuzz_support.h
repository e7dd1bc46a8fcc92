// Shared by the libFuzzer targets (tests/fuzz/*_fuzz.cpp, docs/reliability.md).
//
// The contract every target checks: a reader given any bytes either returns a value or throws
// shatter::Error with the exit code class a user's bad file deserves (BadInput). Anything else is
// a finding: a crash, a sanitizer report, a hang, a leak, an uncaught exception of another type
// (which `shatter` would report as exit 70, "a bug in shatter"), or an Error of another class.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

#include "core/error.h"

namespace shatter::fuzz {

// A per-process scratch file with the given extension (the readers that take a path get the
// fuzzer's bytes through it; the extension is the format hint, as for a user's file).
inline std::string scratch_file(std::string_view bytes, const std::string& extension) {
    const char* dir = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    const std::string path =
        std::string(dir) + "/shatter-fuzz-" + std::to_string(::getpid()) + "." + extension;
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
    return path;
}

// Runs `read`; a shatter::Error of class `expected` is the right answer to bad bytes.
template <class F>
void expect_value_or_error(F&& read, ExitCode expected = ExitCode::BadInput) {
    try {
        read();
    } catch (const Error& e) {
        if (e.code() != expected) {
            std::fprintf(stderr, "fuzz: Error of class %d, not %d: %s\n", int(e.code()), int(expected), e.what());
            std::abort();
        }
    }
}

}  // namespace shatter::fuzz
