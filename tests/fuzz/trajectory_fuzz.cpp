// libFuzzer target: the trajectory reader (decode_trajectory), `shatter info`'s summary of it,
// and the scene that render and the .glb export read back from its settings JSON
// (render/render_scene.cpp, pipeline/export_glb.cpp). Seeds: tests/fuzz/corpus/trajectory/.
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/scene_settings.h"
#include "core/trajectory.h"
#include "core/trajectory_summary.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    shatter::fuzz::expect_value_or_error([&] {
        const shatter::Trajectory t = shatter::decode_trajectory(bytes, "fuzz.traj");
        shatter::trajectory_summary_text(shatter::trajectory_summary(t));
        // As render_scene.cpp reads it: a settings object with a "scene" is a scene.
        const nlohmann::json settings = nlohmann::json::parse(t.settings_json, nullptr, false);
        if (settings.is_object() && settings.contains("scene")) shatter::scene_from_json(settings["scene"], "fuzz.traj");
    });
    return 0;
}
