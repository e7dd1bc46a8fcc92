// An output file that an external tool (ffmpeg) writes: the tool is given a
// temporary name beside the target, and only a finished file is renamed into place (STYLE 8).
//
// The temporary file sits in a folder of its own, TARGET.tmp.PID/: a tool whose parent was killed
// (SIGKILL: nothing to stop the child) may still be writing, and the next run removes the folder
// (pipeline/run.cpp). A tool that opened its file before keeps writing to a removed file; one that
// opens it after finds no folder (ffmpeg makes none); either way no file is
// left under the output's folder.
#pragma once

#include <string>

namespace shatter {

class ToolOutput {
public:
    // Creates TARGET.tmp.PID/output.EXTENSION (tools choose their format by the extension), so an
    // unwritable directory is an Error(Io) naming `target` before the tool runs.
    ToolOutput(const std::string& target, const std::string& extension);
    ~ToolOutput();  // removes the temporary file (unless committed) and its folder
    ToolOutput(const ToolOutput&) = delete;
    ToolOutput& operator=(const ToolOutput&) = delete;

    const std::string& path() const { return tmp_; }  // absolute
    // Renames the temporary file onto the target; Error(Io) when that fails.
    void commit();

private:
    std::string target_, dir_, tmp_;
    bool committed_ = false;
};

}  // namespace shatter
