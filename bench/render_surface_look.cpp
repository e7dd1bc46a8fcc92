// Render surfaces against tet surfaces, side by side in one run: the demo bunny (assets/bunny.toml,
// prescored here: its pieces carry render surfaces) drawn over the render benchmark's synthetic
// 60-frame trajectory at 1280x720 (shadows, 4x MSAA, PNG writing overlapped), once as before
// (the render surfaces removed: each piece's tet surface, flat, unindexed) and once as render
// draws them now (indexed, smooth per-vertex normals on the outer faces). Prints CSV; with an
// output folder as argument, keeps frame 0 of each as tet.png and render.png there. Never fails
// on time.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include <spdlog/spdlog.h>

#include "core/shot.h"
#include "prescore/prescore.h"
#include "render/render.h"
#include "tests/render/render_test_scene.h"

using namespace shatter;

int main(int argc, char** argv) {
    spdlog::set_level(spdlog::level::warn);
    const Shot shot = load_shot(std::string(SHATTER_SOURCE_DIR) + "/assets/bunny.toml");
    const Model render_model = prescore(shot.mesh, shot.prescore, nullptr);
    Model tet_model = render_model;
    for (Piece& p : tet_model.pieces) p.render.reset();
    SceneSettings scene_settings;  // the ground only
    const Trajectory trajectory = testing_support::test_trajectory(tet_model, scene_settings, 60);
    const std::string out = "/tmp/shatter-bench-render-surface";
    std::printf("surface,triangles,frames,seconds,fps\n");
    for (const auto& [name, model] : {std::pair<const char*, const Model*>{"tet", &tet_model}, {"render", &render_model}}) {
        RenderScene scene;
        scene.model = model;
        scene.trajectory = &trajectory;
        scene.scene = scene_settings;
        size_t triangles = 0;
        for (const Piece& p : model->pieces) triangles += p.render ? p.render->triangles.size() : p.surface.triangles.size();
        RenderSettings s;  // 1280x720, shadows, 4x MSAA
        RenderOptions options;
        options.progress = false;
        std::filesystem::remove_all(out);
        render_frames(scene, s, {0, 2}, out, options);  // warm up (shader JIT)
        std::filesystem::remove_all(out);
        const RenderReport r = render_frames(scene, s, {0, trajectory.frames()}, out, options);
        std::printf("%s,%zu,%u,%.3f,%.2f\n", name, triangles, r.frames, r.seconds, r.frames / r.seconds);
        std::fflush(stdout);
        if (argc > 1) {
            std::filesystem::create_directories(argv[1]);
            for (const auto& e : std::filesystem::directory_iterator(out)) {
                if (e.path().filename().string().find("0000") == std::string::npos) continue;
                std::filesystem::copy_file(e.path(), std::filesystem::path(argv[1]) / (std::string(name) + ".png"),
                                           std::filesystem::copy_options::overwrite_existing);
                break;
            }
        }
    }
    std::filesystem::remove_all(out);
    return 0;
}
