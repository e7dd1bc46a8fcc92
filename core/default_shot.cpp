// The default shot of `shatter run MESH` (core/shot.h). Keep in step with assets/bunny.toml:
// tests/core/shot_test.cpp compares every setting but the mesh's path and size, the camera, and
// [object] place (the base of the mesh 1.5 m up: a user's mesh has its own origin, the demo's bunny
// sits on its origin) and [material] stiffen (on here: a mesh whose pieces come out smaller or heavier than the bunny's
// gets the least stiffness its step converges with instead of a refusal).
#include "core/shot.h"

namespace shatter {

const char* const kDefaultShot = R"toml(
[prescore]
pieces = 10
seed = 1
hollow = 0.06
resolution = 20
density = 1100
constraints_per_pair = 16
collision_max_parts = 8
seeds = "impact"

[object]
position = [0, 1.5, 0]
place = "base"

[material]
stiffness = 3e9
strength = 2e4
alpha = 1.0
friction = 0.6
restitution = 0.1
stiffen = true

[simulate]
duration = "auto"
fps = 30
iterations = 20

[render]
width = 1280
height = 720
fov = 40
)toml";

}  // namespace shatter
