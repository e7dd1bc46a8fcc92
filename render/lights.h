// The lights, fixed in relation to the camera so that any camera gets the same look:
//   key  - a directional light (warm white, 1.45) at key_azimuth/key_elevation relative to the
//          camera's direction; the only one that casts shadows;
//   fill - a soft directional light (cool, 0.3) from the other side, 20 degrees high, no shadow;
//   ambient - a hemisphere: sky colour from above, a darker bounce from below.
// The key light's shadow map is an orthographic view along the light that covers the bounding
// sphere of the whole animation (fixed for the render: no swimming, same pixels for any range).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/render_settings.h"
#include "render/camera.h"

namespace shatter {

struct Lights {
    Eigen::Vector3f key_direction;  // unit, from the scene toward the light
    Eigen::Vector3f key_colour;     // linear RGB irradiance scale
    Eigen::Vector3f fill_direction;
    Eigen::Vector3f fill_colour;
    Eigen::Vector3f sky_colour;     // ambient from +y
    Eigen::Vector3f bounce_colour;  // ambient from -y
    Eigen::Matrix4f shadow_view_projection;  // world -> the shadow map's clip space
    float shadow_texel = 0;         // one shadow-map texel (unit: m)
};

Lights make_lights(const Eigen::AlignedBox3d& bounds, const Camera& camera, const RenderSettings& s);

}  // namespace shatter
