// make_render_scene and check_render_limits (render/render.h): everything render checks
// before it draws, so that a mismatch is an error naming the files instead of a wrong picture.
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/binary_io.h"
#include "core/error.h"
#include "meshio/mesh_load.h"
#include "render/render.h"

namespace shatter {

namespace {

// The model hash the trajectory names ({"model": {"fnv1a64": N or "hex"}}), if any.
std::optional<uint64_t> named_model_hash(const nlohmann::json& settings) {
    if (!settings.is_object() || !settings.contains("model") || !settings["model"].is_object()) return std::nullopt;
    const nlohmann::json& m = settings["model"];
    if (!m.contains("fnv1a64")) return std::nullopt;
    if (m["fnv1a64"].is_number_unsigned()) return m["fnv1a64"].get<uint64_t>();
    if (m["fnv1a64"].is_string()) {
        const std::string s = m["fnv1a64"].get<std::string>();
        try {
            return std::stoull(s, nullptr, s.size() == 16 ? 16 : 10);
        } catch (const std::exception&) {
            return std::nullopt;
        }
    }
    return std::nullopt;
}

std::string resolve_mesh_path(const std::string& mesh, const std::string& trajectory_path) {
    std::filesystem::path p(mesh);
    if (p.is_relative() && !std::filesystem::exists(p)) {
        std::filesystem::path beside = std::filesystem::path(trajectory_path).parent_path() / p;
        if (std::filesystem::exists(beside)) return beside.string();
    }
    return mesh;
}

}  // namespace

RenderScene make_render_scene(const Model& model, const std::string& model_path, const Trajectory& trajectory,
                              const std::string& trajectory_path) {
    RenderScene out;
    out.model = &model;
    out.trajectory = &trajectory;
    if (trajectory.pieces != model.pieces.size())
        throw_input_error(trajectory_path,
                          fmt::format("the trajectory moves {} pieces but the model {} has {}", trajectory.pieces,
                                      model_path, model.pieces.size()),
                          "render a trajectory with the model it was simulated from");
    if (trajectory.frames() == 0)
        throw_input_error(trajectory_path, "the trajectory holds no frames", "simulate again (shatter simulate)");
    nlohmann::json settings;
    if (!trajectory.settings_json.empty()) {
        settings = nlohmann::json::parse(trajectory.settings_json, nullptr, false);
        if (settings.is_discarded() || !settings.is_object())
            throw_input_error(trajectory_path, "its settings are not a JSON object", "simulate again");
    }
    if (auto hash = named_model_hash(settings)) {
        const uint64_t actual = fnv1a64(read_file(model_path, "model"));
        if (actual != *hash)
            throw_input_error(trajectory_path,
                              fmt::format("the trajectory was simulated from a model with hash {:016x}, but {} has "
                                          "hash {:016x}", *hash, model_path, actual),
                              "render with the model the trajectory was simulated from, or simulate again");
    }
    if (settings.is_object() && settings.contains("scene")) out.scene = scene_from_json(settings["scene"], trajectory_path);
    if (const size_t props = scene_props(out.scene).size(); trajectory.props != props)
        throw_input_error(trajectory_path,
                          fmt::format("the trajectory moves {} kinematic bodies and projectiles but its scene "
                                      "describes {}", trajectory.props, props),
                          "simulate again; the file is inconsistent");
    out.collider_meshes.resize(out.scene.colliders.size());
    for (size_t i = 0; i < out.scene.colliders.size(); ++i) {
        const ColliderSettings& c = out.scene.colliders[i];
        if (c.shape.kind == ShapeKind::Mesh)
            out.collider_meshes[i] = load_mesh(resolve_mesh_path(c.shape.mesh, trajectory_path), c.shape.mesh_scale);
    }
    return out;
}

void check_render_limits(const RenderSettings& s, int max_image_size, int max_samples, const std::string& where) {
    if (s.width == 0 || s.height == 0 || s.width > uint32_t(max_image_size) || s.height > uint32_t(max_image_size))
        throw Error(ExitCode::Usage, fmt::format("{}: an image of {}x{} pixels is outside what OpenGL allows here "
                                                 "(1 to {} per side; fix: give a size within that, e.g. 1280x720)",
                                                 where, s.width, s.height, max_image_size));
    if (int(s.msaa) > max_samples)
        throw Error(ExitCode::Usage, fmt::format("msaa = {} is more than the {} samples OpenGL offers here (fix: "
                                                 "--msaa {})", s.msaa, max_samples, max_samples));
    if (s.shadows && int(s.shadow_map) > max_image_size)
        throw Error(ExitCode::Usage, fmt::format("shadow_map = {} is more than the {} texels OpenGL allows here "
                                                 "(fix: a smaller render.shadow_map)", s.shadow_map, max_image_size));
}

}  // namespace shatter
