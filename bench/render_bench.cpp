// render benchmark: frames per second for the bunny (assets/bunny.toml, prescored here, 10
// pieces) flying apart over a synthetic 60-frame trajectory, at 1280x720 with shadows and the
// edge filter (the defaults), PNG writing included; and where the time goes (draw = shadow +
// scene + resolve passes rasterized, readback, edge filter, PNG encode, file write). The second
// row, side by side with the first, is 4x MSAA instead of the filter; then rows for MSAA over the
// whole frame, the PNG writer on the main thread ("serial") instead of overlapped on a second
// thread ("overlap", what `shatter render` does), and cheaper settings. Prints CSV; never fails on
// time. Goal (docs/benchmarks.md): >= 20 frames/s in total.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/log.h"
#include "core/shot.h"
#include "prescore/prescore.h"
#include "render/render.h"
#include "scenes/render_test_scene.h"

using namespace shatter;

int main(int argc, char** argv) {
    setup_logging("warn");  // to standard error: standard output is the CSV
    const std::string shot_path = argc > 1 ? argv[1] : std::string(SHATTER_SOURCE_DIR) + "/assets/bunny.toml";
    const Shot shot = load_shot(shot_path);
    const Model model = prescore(shot.mesh, shot.prescore, nullptr);
    SceneSettings scene_settings;  // the ground only
    const Trajectory trajectory = testing_support::test_trajectory(model, scene_settings, 60);
    RenderScene scene;
    scene.model = &model;
    scene.trajectory = &trajectory;
    scene.scene = scene_settings;
    size_t triangles = 0;
    for (const Piece& p : model.pieces) triangles += p.render ? p.render->triangles.size() : p.surface.triangles.size();

    const std::string out = "/tmp/shatter-bench-render";
    std::printf("scene,width,height,shadows,shadow_map,msaa,msaa_region,edge_filter,png_writer,frames,triangles,seconds,fps,draw_ms,"
                "readback_ms,filter_ms,encode_ms,write_ms,mb_per_frame\n");
    struct Row {
        bool shadows;
        uint32_t msaa;
        bool overlap;
        uint32_t shadow_map;
        MsaaRegion region = MsaaRegion::Edges;
        bool filter = false;
    };
    const bool quick = std::getenv("SHATTER_BENCH_QUICK") != nullptr;  // the first two rows only
    for (const Row& row : {Row{true, 1, true, 1024, MsaaRegion::Edges, true}, Row{true, 4, true, 1024},
                           Row{true, 4, true, 1024, MsaaRegion::Everywhere}, Row{true, 1, false, 1024, MsaaRegion::Edges, true},
                           Row{true, 1, true, 2048, MsaaRegion::Edges, true}, Row{false, 1, true, 1024, MsaaRegion::Edges, true},
                           Row{true, 1, true, 1024}, Row{false, 1, true, 1024}}) {
        RenderSettings s;  // 1280x720
        s.shadow_map = row.shadow_map;
        s.shadows = row.shadows;
        s.msaa = row.msaa;
        s.edge_filter = row.filter;
        RenderOptions options;
        options.progress = false;
        options.overlap = row.overlap;
        options.msaa_region = row.region;
        std::filesystem::remove_all(out);
        render_frames(scene, s, {0, 2}, out, options);  // warm up: shader compilation (JIT)
        std::filesystem::remove_all(out);
        const RenderReport r = render_frames(scene, s, {0, trajectory.frames()}, out, options);
        uintmax_t bytes = 0;
        for (const auto& e : std::filesystem::directory_iterator(out)) bytes += e.file_size();
        const double n = r.frames;
        std::printf("bunny,%u,%u,%d,%u,%u,%s,%d,%s,%u,%zu,%.3f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f\n", s.width, s.height,
                    s.shadows, s.shadow_map, s.msaa,
                    s.msaa == 1 ? "-" : row.region == MsaaRegion::Edges ? "edges" : "everywhere", s.edge_filter,
                    row.overlap ? "overlap" : "serial", r.frames, triangles, r.seconds, n / r.seconds,
                    1e3 * r.draw_seconds / n, 1e3 * r.readback_seconds / n, 1e3 * r.filter_seconds / n,
                    1e3 * r.encode_seconds / n, 1e3 * r.write_seconds / n, double(bytes) / n / 1e6);
        std::fflush(stdout);
        if (quick && s.msaa == 4) break;
    }
    if (!std::getenv("SHATTER_BENCH_KEEP")) std::filesystem::remove_all(out);  // keep: to look at the frames
    return 0;
}
