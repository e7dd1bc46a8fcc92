// Finding an external program on PATH: ffmpeg, python3 and sbatch for the pipeline, blender for a
// reader's advice.
#pragma once

#include <optional>
#include <string>

namespace shatter {

// The full path of `name` searched on PATH (or `name` itself when it contains a '/' and is
// executable); nullopt when not found.
std::optional<std::string> find_program(const std::string& name);

}  // namespace shatter
