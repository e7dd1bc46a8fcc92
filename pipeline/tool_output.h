// An output file that an external tool (ffmpeg, matplotlib) writes: the tool is given a
// temporary name beside the target, and only a finished file is renamed into place (STYLE 8).
#pragma once

#include <string>

namespace shatter {

class ToolOutput {
public:
    // Creates TARGET.tmp.PID.EXTENSION (tools choose their format by the extension), so an
    // unwritable directory is an Error(Io) naming `target` before the tool runs.
    ToolOutput(const std::string& target, const std::string& extension);
    ~ToolOutput();  // removes the temporary file unless committed
    ToolOutput(const ToolOutput&) = delete;
    ToolOutput& operator=(const ToolOutput&) = delete;

    const std::string& path() const { return tmp_; }  // absolute
    // Renames the temporary file onto the target; Error(Io) when that fails.
    void commit();

private:
    std::string target_, tmp_;
    bool committed_ = false;
};

}  // namespace shatter
