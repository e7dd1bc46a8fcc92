// The camera: a perspective view of the world, y up. By default it frames the whole animation
// (render/scene_bounds.h): it looks at the centre of the animation's box from 30 degrees right
// of +z and 22 degrees above the horizon, from the nearest distance at which every body's ball
// in every frame falls inside the inner 90% of the image (each ball's extent taken as its
// centre's offset plus its radius, a slight over-estimate). A shot may place it
// (camera_position, camera_target).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/render_settings.h"
#include "render/scene_bounds.h"

namespace shatter {

struct Camera {
    Eigen::Vector3f position;
    Eigen::Vector3f target;
    Eigen::Matrix4f view;
    Eigen::Matrix4f projection;  // OpenGL clip space, depth -1..1
};

Eigen::Matrix4f look_at(const Eigen::Vector3f& eye, const Eigen::Vector3f& target, const Eigen::Vector3f& up);
Eigen::Matrix4f perspective(float fovy_radians, float aspect, float near, float far);
Eigen::Matrix4f orthographic(float half_width, float half_height, float near, float far);

// `balls` empty: the eight corners of `bounds` are framed instead.
Camera make_camera(const Eigen::AlignedBox3d& bounds, const std::vector<Ball>& balls, const RenderSettings& s);

// The automatic cameras' view direction, from the target toward the eye: 30 degrees right of
// +z, 22 degrees above the horizon.
Vec3 auto_view_direction();
inline constexpr double kAutoFill = 0.9;  // framed balls fill the inner 90% of the image
// A camera at `eye` looking at `target`, its near and far planes enclosing `bounds` (the whole
// animation) and the ground out to where it has faded.
Camera camera_looking(const Vec3& eye, const Vec3& target, const Eigen::AlignedBox3d& bounds, const RenderSettings& s);

}  // namespace shatter
