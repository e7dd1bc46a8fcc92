// The small shot the pipeline tests run: the 10 cm fixture cube in 4 pieces dropped from 0.5 m,
// 16 frames of 160x90. A couple of seconds from mesh to movie.
#pragma once

#include <filesystem>
#include <string>

#include "support/temp_dir.h"

namespace shatter::testing_support {

inline const char* kCubeShot = R"([mesh]
path = "cube.obj"
scale = 0.1
[prescore]
pieces = 4
resolution = 5
density = 1000
[object]
position = [0, 0.5, 0]
[material]
stiffness = 1e12
strength = 2e3
[simulate]
duration = 0.5
[render]
width = 160
height = 90
shadow_map = 512
)";

// Writes DIR/cube.toml and DIR/cube.obj; returns the shot's path.
inline std::string write_cube_shot(const TempDir& dir) {
    std::filesystem::copy_file(SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", dir.file("cube.obj"));
    return dir.write("cube.toml", kCubeShot);
}

// A batch file beside the cube shot: an alpha sweep of two runs, and a job that fails (an image
// 100,000 pixels wide), for the batch tests.
inline const char* kCubeSweepBatch = R"([batch]
workers = 2

[[job]]
shot = "cube.toml"
sweep = { "material.alpha" = [0, 2] }

[[job]]
name = "bad"
shot = "cube.toml"
set = { "render.width" = 100000 }
)";

}  // namespace shatter::testing_support
