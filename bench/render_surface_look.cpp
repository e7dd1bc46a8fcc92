// Render surfaces against tet surfaces, and the edge filter against 4x MSAA, side by side in one
// run: the demo bunny (assets/bunny.toml, prescored here: its pieces carry render surfaces) drawn
// over the render benchmark's synthetic 60-frame trajectory at 1280x720 (shadows, PNG writing
// overlapped). Rows: "tet", the render surfaces removed (each piece's tet surface, flat,
// unindexed), 4x MSAA; "render", the render surfaces (indexed, smooth per-vertex normals on the
// outer faces), 4x MSAA; "render-msaa1", one sample per pixel and no filter; "render-filter", one
// sample and the edge filter (the defaults). Prints CSV; with an output folder as argument, keeps
// frame 0 of each as NAME.png there. Never fails on time.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include <sys/resource.h>

#include <spdlog/spdlog.h>

#include "core/shot.h"
#include "prescore/prescore.h"
#include "render/render.h"
#include "scenes/render_test_scene.h"

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
    // CPU seconds of every thread (llvmpipe's, the PNG writer's) as well as the wall clock: on a
    // shared machine the wall clock is mostly the other work's; CPU time per frame is not.
    auto cpu = [] {
        rusage u{};
        getrusage(RUSAGE_SELF, &u);
        return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
    };
    std::printf("surface,triangles,frames,seconds,fps,cpu_ms_per_frame\n");
    struct Row {
        const char* name;
        const Model* model;
        uint32_t msaa;  // samples per pixel
        bool filter;    // the edge filter
    };
    for (const auto& [name, model, msaa, filter] : {Row{"tet", &tet_model, 4, false}, Row{"render", &render_model, 4, false},
                                                    Row{"render-msaa1", &render_model, 1, false},
                                                    Row{"render-filter", &render_model, 1, true}}) {
        RenderScene scene;
        scene.model = model;
        scene.trajectory = &trajectory;
        scene.scene = scene_settings;
        size_t triangles = 0;
        for (const Piece& p : model->pieces) triangles += p.render ? p.render->triangles.size() : p.surface.triangles.size();
        RenderSettings s;  // 1280x720, shadows
        s.msaa = msaa;
        s.edge_filter = filter;
        RenderOptions options;
        options.progress = false;
        std::filesystem::remove_all(out);
        render_frames(scene, s, {0, 2}, out, options);  // warm up (shader JIT)
        std::filesystem::remove_all(out);
        const double cpu0 = cpu();
        const RenderReport r = render_frames(scene, s, {0, trajectory.frames()}, out, options);
        const double cpu_ms = 1e3 * (cpu() - cpu0) / r.frames;
        std::printf("%s,%zu,%u,%.3f,%.2f,%.1f\n", name, triangles, r.frames, r.seconds, r.frames / r.seconds, cpu_ms);
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
