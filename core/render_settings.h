// Settings of render: the shot's [render] section (docs/shot.md) and the flags of
// `shatter render`. Owned by the render stage's design (docs/render.md); defaults give a
// 1280x720 review render with a shadowed key light, anti-aliased by the edge filter. Colours are
// written as sRGB ("#rrggbb", as a colour picker shows them) and held here as linear RGB in [0, 1].
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/geometry.h"
#include "core/settings.h"

namespace shatter {

// What colours the pieces: input: the input's materials, textures and vertex colours (a model
// without any: material_colour); palette: a palette colour by piece id (for reviewing pieces);
// material: material_colour for every piece.
enum class Colours { Input, Palette, Material };
// The camera when the shot places none (no camera_position): "follow" frames the object at the
// start and its fragments after, moving smoothly with them (render/camera_path.h); "whole" stays
// fixed, framing the whole animation at once.
enum class CameraMode { Follow, Whole };

struct RenderSettings {
    uint32_t width = 1280;   // (unit: pixels)
    uint32_t height = 720;   // (unit: pixels)
    // The camera; both unset: framed on the whole animation (its bounds over every frame). A
    // position without a target looks at the centre of those bounds.
    std::optional<Vec3> camera_position;  // (unit: m, world)
    std::optional<Vec3> camera_target;    // (unit: m, world)
    CameraMode camera = CameraMode::Follow;  // without camera_position: follow the pieces, or frame the whole animation
    double fov = 35;                      // vertical field of view (unit: degrees)
    bool shadows = true;                  // the key light casts shadows (shadow map)
    uint32_t shadow_map = 1024;           // shadow map width and height (unit: texels)
    uint32_t msaa = 1;                    // samples per pixel: 1 (off), 2 or 4
    bool edge_filter = true;              // anti-alias the finished image (render/edge_filter.h)
    double key_azimuth = -40;             // key light direction, from the camera's direction about +Y, positive to the right (unit: degrees)
    double key_elevation = 50;            // key light height above the horizon (unit: degrees)
    Colours colours = Colours::Input;
    std::array<float, 3> material_colour = {0.7084f, 0.6514f, 0.5520f};  // linear RGB ("#dbd3c4")
    // Pieces drawn in their own colour whatever the colour mode (the chain's blue end cubes):
    // (piece index, linear RGB), from [render] piece_colours = [{piece = 0, colour = "#2f5fd0"}].
    std::vector<std::pair<uint32_t, std::array<float, 3>>> piece_colours;
    // Fracture faces in this colour (linear RGB), textured or not; unset: the colour of the
    // material around them (its base colour times its texture's mean) tinted by fracture_tint.
    std::optional<std::array<float, 3>> interior_colour;
    // Fracture faces drawn with this image (absolute, or as given; a shot's path is made relative
    // to its folder when read), times interior_colour when set; empty: none. Projected from the
    // three axes in the unbroken object's frame (render/shaders.cpp), so both sides of a crack
    // show the same texture, and one repeat spans interior_texture_size (0: a quarter of the
    // object's bounding-box diagonal).
    std::string interior_texture;
    double interior_texture_size = 0;  // (unit: m)
    double fracture_tint = 0.55;          // fracture faces: this fraction of the way from the piece colour to white (unit: 1)
    double cavity_shade = 0.45;           // cavity faces: the piece colour times this (unit: 1)
    std::array<float, 3> background = {0.5776f, 0.6445f, 0.7231f};  // linear RGB ("#c8d2dd")
};
inline constexpr Limits kImageSizeLimits{1, 16384, "pixels"};
inline constexpr Limits kFovLimits{1, 170, "degrees"};
inline constexpr Limits kShadowMapLimits{64, 8192, "texels"};
inline constexpr Limits kAzimuthLimits{-360, 360, "degrees"};
inline constexpr Limits kElevationLimits{1, 90, "degrees"};
inline constexpr Limits kTintLimits{0, 1, "(fraction)"};
inline constexpr Limits kTextureSizeLimits{0, 1e6, "m"};

const char* to_string(Colours m);
const char* to_string(CameraMode m);
// "#rrggbb" (sRGB) to linear RGB; nullopt when the text is not of that form.
std::optional<std::array<float, 3>> parse_srgb_hex(const std::string& text);
std::string srgb_hex(const std::array<float, 3>& linear);
// Throws Error(Usage when from a flag, else BadInput) when msaa is not 1, 2 or 4.
void check_msaa(const std::string& where, uint32_t msaa, bool from_flag);

nlohmann::ordered_json to_json(const RenderSettings& s);

}  // namespace shatter
