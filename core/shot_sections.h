// The hand-written parts of the shot reader (private to core/shot.cpp, core/setting_table*.cpp
// and the section files): arrays of tables, composite values and checks that join keys. The
// scalar keys of every section are declared in core/setting_table_*.cpp.
#pragma once

#include <string>

#include "core/generate_settings.h"
#include "core/render_settings.h"
#include "core/scene_settings.h"
#include "core/toml_reader.h"

namespace shatter {

inline constexpr Limits kGravityLimits{-1e3, 1e3, "m/s^2"};
inline constexpr Limits kPositionLimits{-1e6, 1e6, "m"};
inline constexpr Limits kRotationLimits{-360, 360, "degrees"};
inline constexpr Limits kVelocityLimits{-1e4, 1e4, "m/s"};
inline constexpr Limits kAngularVelocityLimits{-1e4, 1e4, "rad/s"};

// [[scene.colliders]] and [[scene.kinematic]] (core/shot_scene.cpp); mesh files are taken
// relative to `shot_path`'s folder.
void read_scene_arrays(TomlSection& s, SceneSettings& scene, const std::string& shot_path);
// keys = [[t, x, y, z], ...] of a kinematic body or a driven piece (core/shot_scene.cpp), its
// JSON (the same arrays; [] for none) and the JSON read back (times strictly increasing).
void read_keys(TomlSection& s, std::vector<KeyFrame>& keys);
nlohmann::ordered_json keys_json(const std::vector<KeyFrame>& keys);
class JsonObject;
std::vector<KeyFrame> keys_from_json(JsonObject& o, const char* key);
// [[object.driven]] (core/shot_scene.cpp).
void read_object_driven(TomlSection& s, ObjectSettings& object);
// An array of `n` numbers under `key`, each within `limits`; `example` is a valid value for the
// fix (core/shot_scene.cpp). False when the key is absent.
bool read_numbers(TomlSection& s, const char* key, double* out, size_t n, const Limits& limits, const char* example);

// [render] (core/shot_render.cpp): a camera point [x, y, z], an sRGB "#rrggbb" colour, the
// piece_colours array, and the checks that join camera_position and camera_target.
bool read_render_point(TomlSection& s, const char* key, std::optional<Vec3>& out);
void read_srgb_colour(TomlSection& s, const char* key, std::array<float, 3>& out);
void read_piece_colours(TomlSection& s, std::vector<std::pair<uint32_t, std::array<float, 3>>>& out);
void check_render_camera(TomlSection& s, const RenderSettings& r);
// Their JSON: the point (when set) and piece_colours (when not empty).
void put_render_point(nlohmann::ordered_json& j, const char* key, const std::optional<Vec3>& point);
void put_piece_colours(nlohmann::ordered_json& j, const std::vector<std::pair<uint32_t, std::array<float, 3>>>& pieces);

}  // namespace shatter
