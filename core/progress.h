// Progress of a slow loop, on stderr: a bar redrawn in place on a terminal; on a pipe or in CI,
// a line at every tenth. Quiet for loops that end quickly, and when the log level is above info.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace shatter {

class Progress {
public:
    Progress(std::string label, size_t total);
    ~Progress();
    void advance(size_t n = 1);
    void done();

private:
    void draw(bool final);
    std::string label_;
    size_t total_;
    size_t count_ = 0;
    int last_tenth_ = -1;
    int last_width_ = -1;
    bool tty_ = false;
    bool enabled_ = false;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace shatter
