// The readers of each shot-file section (private to core/shot.cpp and its section files).
#pragma once

#include <string>

#include "core/render_settings.h"
#include "core/scene_settings.h"
#include "core/toml_reader.h"

namespace shatter {

// [scene] with its [[scene.colliders]] and [[scene.kinematic]] arrays (core/shot_scene.cpp).
void read_scene_section(TomlSection& s, SceneSettings& scene, const std::string& shot_path);
void read_object_section(TomlSection& s, ObjectSettings& object);
void read_material_section(TomlSection& s, MaterialSettings& material);
void read_simulate_section(TomlSection& s, SimulateSettings& simulate);
// [render] (core/shot_render.cpp).
void read_render_section(TomlSection& s, RenderSettings& render);

}  // namespace shatter
