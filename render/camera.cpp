#include "render/camera.h"

#include <algorithm>
#include <cmath>

namespace shatter {

namespace {

constexpr double kAutoAzimuth = 30 * M_PI / 180;    // right of +z
constexpr double kAutoElevation = 22 * M_PI / 180;  // above the horizon

// An up vector not parallel to the view direction.
Eigen::Vector3f up_for(const Eigen::Vector3f& forward) {
    return std::abs(forward.normalized().y()) > 0.999f ? Eigen::Vector3f(0, 0, -1) : Eigen::Vector3f(0, 1, 0);
}

}  // namespace

Eigen::Matrix4f look_at(const Eigen::Vector3f& eye, const Eigen::Vector3f& target, const Eigen::Vector3f& up) {
    const Eigen::Vector3f f = (target - eye).normalized();
    const Eigen::Vector3f r = f.cross(up).normalized();
    const Eigen::Vector3f u = r.cross(f);
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    m.block<1, 3>(0, 0) = r.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -r.dot(eye);
    m(1, 3) = -u.dot(eye);
    m(2, 3) = f.dot(eye);
    return m;
}

Eigen::Matrix4f perspective(float fovy, float aspect, float near, float far) {
    const float t = 1.0f / std::tan(fovy / 2);
    Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
    m(0, 0) = t / aspect;
    m(1, 1) = t;
    m(2, 2) = (far + near) / (near - far);
    m(2, 3) = 2 * far * near / (near - far);
    m(3, 2) = -1;
    return m;
}

Eigen::Matrix4f orthographic(float hw, float hh, float near, float far) {
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    m(0, 0) = 1 / hw;
    m(1, 1) = 1 / hh;
    m(2, 2) = -2 / (far - near);
    m(2, 3) = -(far + near) / (far - near);
    return m;
}

Camera make_camera(const Eigen::AlignedBox3d& bounds, const std::vector<Ball>& balls, const RenderSettings& s) {
    const double aspect = double(s.width) / s.height;
    const double tan_v = std::tan(s.fov * M_PI / 360), tan_h = tan_v * aspect;
    const Vec3 centre = bounds.center();
    Vec3 eye, target = centre;
    if (s.camera_position) {
        eye = *s.camera_position;
        if (s.camera_target) target = *s.camera_target;
    } else {
        const Vec3 dir = auto_view_direction();
        // Camera basis: right, up, and `dir` pointing back toward the eye.
        const Vec3 right = Vec3(0, 1, 0).cross(dir).normalized(), up = dir.cross(right);
        double distance = 0;
        auto fit = [&](const Vec3& point, double r) {
            const Vec3 q = point - centre;
            const double depth = q.dot(dir);  // toward the eye
            distance = std::max(distance, depth + (std::abs(q.dot(right)) + r) / (kAutoFill * tan_h));
            distance = std::max(distance, depth + (std::abs(q.dot(up)) + r) / (kAutoFill * tan_v));
        };
        for (const Ball& b : balls) fit(b.centre, b.radius);
        if (balls.empty())
            for (int i = 0; i < 8; ++i) fit(bounds.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)), 0);
        eye = centre + dir * distance;
    }
    return camera_looking(eye, target, bounds, s);
}

Vec3 auto_view_direction() {
    return Vec3(std::sin(kAutoAzimuth) * std::cos(kAutoElevation), std::sin(kAutoElevation),
                std::cos(kAutoAzimuth) * std::cos(kAutoElevation));
}

Camera camera_looking(const Vec3& eye, const Vec3& target, const Eigen::AlignedBox3d& bounds, const RenderSettings& s) {
    const double aspect = double(s.width) / s.height;
    const Vec3 centre = bounds.center();
    const double radius = bounds.sizes().norm() / 2;
    Camera c;
    c.position = eye.cast<float>();
    c.target = target.cast<float>();
    const Eigen::Vector3f forward = c.target - c.position;
    c.view = look_at(c.position, c.target, up_for(forward));
    // Near and far enclose the animation and the ground out to where it has faded (12 radii).
    const double to_centre = (centre - eye).norm();
    const double far = to_centre + 14 * radius;
    const double near = std::max({to_centre - 2 * radius, far * 1e-4, 1e-4});
    c.projection = perspective(static_cast<float>(s.fov * M_PI / 180), static_cast<float>(aspect),
                               static_cast<float>(near), static_cast<float>(far));
    return c;
}

}  // namespace shatter
