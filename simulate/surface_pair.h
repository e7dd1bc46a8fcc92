#pragma once
// How two surfaces in contact combine their friction and restitution (docs/physics.md section 5d).
// A material against itself keeps its own figures, as the presets and docs/shot.md give them:
// friction is the geometric mean of the two coefficients, restitution the larger of the two.
// Bullet's own rule multiplies both (ice on ice 0.0025 for ice's 0.05; two surfaces of
// restitution 0.1 bounce at 0.01).

#include <algorithm>
#include <cmath>

namespace shatter {

inline double pair_friction(double a, double b) { return std::sqrt(a * b); }
inline double pair_restitution(double a, double b) { return std::max(a, b); }

}  // namespace shatter
