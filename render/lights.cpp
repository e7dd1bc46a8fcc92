#include "render/lights.h"

#include <cmath>

namespace shatter {

namespace {

// The direction at `azimuth` degrees (positive: to the camera's right) from the horizontal
// direction toward the camera, `elevation` degrees above the horizon.
Eigen::Vector3f direction(const Camera& camera, double azimuth, double elevation) {
    Eigen::Vector3f back = camera.position - camera.target;
    back.y() = 0;
    if (back.norm() < 1e-6f) back = Eigen::Vector3f(0, 0, 1);  // looking straight down
    back.normalize();
    const Eigen::Vector3f right = Eigen::Vector3f(0, 1, 0).cross(back).normalized();
    const float a = static_cast<float>(azimuth * M_PI / 180), e = static_cast<float>(elevation * M_PI / 180);
    const Eigen::Vector3f horizontal = std::cos(a) * back + std::sin(a) * right;
    return (std::cos(e) * horizontal + std::sin(e) * Eigen::Vector3f(0, 1, 0)).normalized();
}

}  // namespace

Lights make_lights(const Eigen::AlignedBox3d& bounds, const Camera& camera, const RenderSettings& s) {
    Lights l;
    l.key_direction = direction(camera, s.key_azimuth, s.key_elevation);
    l.key_colour = Eigen::Vector3f(1.0f, 0.96f, 0.90f) * 1.45f;
    l.fill_direction = direction(camera, s.key_azimuth >= 0 ? -70 : 70, 20);
    l.fill_colour = Eigen::Vector3f(0.80f, 0.88f, 1.0f) * 0.30f;
    l.sky_colour = Eigen::Vector3f(0.80f, 0.88f, 1.0f) * 0.32f;
    l.bounce_colour = Eigen::Vector3f(1.0f, 0.95f, 0.90f) * 0.10f;

    const Eigen::Vector3f centre = bounds.center().cast<float>();
    const float r = static_cast<float>(bounds.sizes().norm() / 2);
    const Eigen::Vector3f eye = centre + l.key_direction * (2 * r);
    const Eigen::Vector3f up = std::abs(l.key_direction.y()) > 0.999f ? Eigen::Vector3f(0, 0, -1)
                                                                      : Eigen::Vector3f(0, 1, 0);
    l.shadow_view_projection = orthographic(r, r, 0.9f * r, 3.1f * r) * look_at(eye, centre, up);
    l.shadow_texel = 2 * r / static_cast<float>(s.shadow_map);
    return l;
}

}  // namespace shatter
