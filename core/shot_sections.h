// The readers of each shot-file section (private to core/shot.cpp and its section files).
#pragma once

#include <string>

#include "core/generate_settings.h"
#include "core/render_settings.h"
#include "core/scene_settings.h"
#include "core/toml_reader.h"

namespace shatter {

// [scene] with its [[scene.colliders]] and [[scene.kinematic]] arrays (core/shot_scene.cpp).
void read_scene_section(TomlSection& s, SceneSettings& scene, const std::string& shot_path);
void read_object_section(TomlSection& s, ObjectSettings& object);
void read_material_section(TomlSection& s, MaterialSettings& material);
void read_simulate_section(TomlSection& s, SimulateSettings& simulate);
// [generate] (core/shot_generate.cpp).
void read_generate_section(TomlSection& s, GenerateSettings& generate);
// An array of `n` numbers under `key`, each within `limits`; `example` is a valid value for the
// fix (core/shot_scene.cpp). False when the key is absent.
bool read_numbers(TomlSection& s, const char* key, double* out, size_t n, const Limits& limits, const char* example);
// [render] (core/shot_render.cpp).
void read_render_section(TomlSection& s, RenderSettings& render);

}  // namespace shatter
