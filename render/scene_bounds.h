// The box the whole animation lives in: every piece over every frame (its centre of mass
// position plus the radius of its surface about that centre), every kinematic body over every
// frame, and the static colliders of finite size. The automatic camera frames this box and the
// key light's shadow map covers it; both are fixed for the whole render, which keeps a frame's
// pixels independent of the range rendered and avoids shadows that swim from frame to frame.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "render/render.h"

namespace shatter {

// Radius of a shape about its origin (unit: m); 0 for a plane or a mesh.
double shape_radius(const ShapeSettings& shape);

struct Ball {
    Vec3 centre;    // (unit: m)
    double radius;  // (unit: m)
};
// A ball around every piece and kinematic body in every frame, and around each finite static
// collider (boxes, spheres; planes and meshes are scenery and left out).
std::vector<Ball> animation_balls(const RenderScene& scene);
// The ground fades into the background colour from kFadeStart to kFadeEnd, measured
// horizontally from the centre of the animation's box (unit: the box's half-diagonal).
inline constexpr double kFadeStart = 2.5, kFadeEnd = 8;
// The box around those balls, at least 10 cm on each side.
Eigen::AlignedBox3d animation_bounds(const std::vector<Ball>& balls);
inline Eigen::AlignedBox3d animation_bounds(const RenderScene& scene) { return animation_bounds(animation_balls(scene)); }

}  // namespace shatter
